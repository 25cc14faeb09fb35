// White furnace tests per BSDF: the directional albedo, estimated by sampling, never
// exceeds 1 (energy conservation), equals the reflectance for lossless or Lambertian
// lobes, and the sampled weights agree with f·cos/pdf from evaluation.
#include <gtest/gtest.h>

#include <cmath>

#include "statmc/render/bsdf.h"
#include "statmc/render/sampler.h"

using namespace statmc::render;

namespace {

constexpr int kSamples = 200000;

Vec3 direction(float cos_theta, float phi)
{
    const float s = std::sqrt(std::max(0.f, 1 - cos_theta * cos_theta));
    return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

/// Mean sample weight for outgoing direction wo (the directional albedo, per channel).
template <class Lobe>
Rgb albedo(const Lobe& lobe, Vec3 wo, std::uint64_t seed)
{
    Sampler rng(seed, 0, 0);
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < kSamples; ++i) {
        const float u1 = rng.get1d(), u2 = rng.get1d(), uc = rng.get1d();
        if (auto s = lobe.sample(wo, u1, u2, uc))
            for (int c = 0; c < 3; ++c)
                sum[c] += s->weight[c];
    }
    return {float(sum[0] / kSamples), float(sum[1] / kSamples), float(sum[2] / kSamples)};
}

}  // namespace

TEST(Furnace, MatteReflectsItsAlbedo)
{
    const MatteLobe lobe{Rgb{0.2f, 0.5f, 0.8f}};
    for (float cos_o : {0.1f, 0.5f, 1.f, -0.7f}) {  // both sides: pbrt's BxDFs are two-sided
        const Rgb a = albedo(lobe, direction(cos_o, 0.3f), 1);
        EXPECT_NEAR(a.r, 0.2f, 1e-5f);
        EXPECT_NEAR(a.g, 0.5f, 1e-5f);
        EXPECT_NEAR(a.b, 0.8f, 1e-5f);
    }
}

TEST(Furnace, MirrorIsLossless)
{
    const MirrorLobe lobe{Rgb{1.f}};
    const Rgb a = albedo(lobe, direction(0.4f, 1.f), 2);
    EXPECT_FLOAT_EQ(a.g, 1.f);
}

TEST(Furnace, GlassIsLosslessUpToTheRadianceScale)
{
    // Reflected plus transmitted energy is 1 once the (η_i/η_t)² radiance scaling of the
    // refracted branch is undone (it conserves radiance·area, not radiance).
    const GlassLobe lobe{Rgb{1.f}, Rgb{1.f}, 1.5f};
    for (float cos_o : {0.9f, 0.3f, -0.9f, -0.3f}) {
        const Vec3 wo = direction(cos_o, 0.7f);
        Sampler rng(3, 0, 0);
        double energy = 0;
        for (int i = 0; i < kSamples; ++i) {
            const auto s = lobe.sample(wo, rng.get1d(), rng.get1d(), rng.get1d());
            ASSERT_TRUE(s);
            const bool refracted = s->wi.z * wo.z < 0;
            const float eta = wo.z > 0 ? 1.f / 1.5f : 1.5f;  // η_i/η_t
            energy += refracted ? s->weight.g / (eta * eta) : s->weight.g;
            EXPECT_NEAR(length(s->wi), 1.f, 1e-5f);
        }
        EXPECT_NEAR(energy / kSamples, 1.0, 1e-6) << "cos_o " << cos_o;
    }
}

TEST(Furnace, RoughMetalConservesEnergy)
{
    // A conductor with huge k reflects (almost) everything: the albedo is then the
    // microfacet model's own, ≤ 1 and close to 1 at low roughness (single scattering
    // loses some energy at high roughness and grazing angles).
    const Rgb eta{0.2f}, k{1e3f};
    for (float alpha : {0.01f, 0.1f, 0.25f, 0.6f}) {
        const MetalLobe lobe{eta, k, alpha, alpha};
        for (float cos_o : {0.2f, 0.6f, 1.f}) {
            const Rgb a = albedo(lobe, direction(cos_o, 0.4f), 4);
            EXPECT_LE(a.g, 1.f + 2e-3f) << "alpha " << alpha << " cos " << cos_o;
            if (alpha <= 0.1f && cos_o >= 0.6f) {
                EXPECT_GT(a.g, 0.97f) << "alpha " << alpha << " cos " << cos_o;
            }
        }
    }
}

TEST(Furnace, MetalSamplingAgreesWithEvaluation)
{
    // The same albedo by uniform hemisphere sampling of f·cos (no importance sampling):
    // checks that sample(), f() and pdf() describe one BSDF. Anisotropic alphas.
    const MetalLobe lobe{Rgb{0.2f, 0.9f, 1.1f}, Rgb{3.9f, 2.4f, 2.1f}, 0.3f, 0.15f};
    const Vec3 wo = direction(0.7f, 0.9f);
    Sampler rng(5, 0, 0);
    double uniform = 0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        const float z = rng.get1d(), phi = 2 * kPi * rng.get1d();
        const Vec3 wi = direction(z, phi);
        uniform += lobe.f(wo, wi).g * wi.z * (2 * kPi);
    }
    uniform /= n;
    const Rgb importance = albedo(lobe, wo, 6);
    EXPECT_NEAR(importance.g, uniform, 0.01);
    // Per sample: weight == f·cos/pdf.
    for (int i = 0; i < 1000; ++i) {
        const auto s = lobe.sample(wo, rng.get1d(), rng.get1d(), 0.f);
        if (!s)
            continue;
        const float expect = lobe.f(wo, s->wi).g * s->wi.z / lobe.pdf(wo, s->wi);
        EXPECT_NEAR(s->weight.g, expect, 1e-3f * std::max(1.f, expect));
        EXPECT_NEAR(s->pdf, lobe.pdf(wo, s->wi), 1e-3f * s->pdf);
    }
}

TEST(Furnace, ConductorFresnelMatchesKnownValues)
{
    // Normal incidence: ((η−1)² + k²) / ((η+1)² + k²).
    const Rgb F = fresnel_conductor(1.f, Rgb{0.2f}, Rgb{3.9f});
    EXPECT_NEAR(F.r, (0.64f + 15.21f) / (1.44f + 15.21f), 1e-4f);
    // Dielectric: 4% at normal incidence for η = 1.5, total internal reflection inside.
    EXPECT_NEAR(fresnel_dielectric(1.f, 1.5f), 0.04f, 1e-5f);
    EXPECT_FLOAT_EQ(fresnel_dielectric(-0.2f, 1.5f), 1.f);
}

TEST(Furnace, AnisotropyFollowsTheTangent)
{
    // αu (along the tangent, dp/du) narrow, αv wide: the lobe is stretched across the
    // tangent. Rotating the tangent by 90° swaps which offset direction is brighter.
    const MetalLobe lobe{Rgb{0.2f}, Rgb{3.9f}, 0.05f, 0.5f};
    const Vec3 n{0, 0, 1}, wo{0, 0, 1};
    const Vec3 along_x = normalize(Vec3{0.3f, 0, 1}), along_y = normalize(Vec3{0, 0.3f, 1});
    const Bsdf tangent_x(lobe, n, n, {2, 0, 0}), tangent_y(lobe, n, n, {0, 1, 0.5f});
    EXPECT_LT(tangent_x.f(wo, along_x).g, tangent_x.f(wo, along_y).g);
    EXPECT_GT(tangent_y.f(wo, along_x).g, tangent_y.f(wo, along_y).g);
}
