// A BSDF at one surface point: the lobe of one material in a local shading frame. Each
// lobe lives in its own file (matte, metal, glass, mirror) and works in local
// coordinates (z = shading normal); Bsdf adds the frame and pbrt's geometric-normal test.
#pragma once

#include <optional>
#include <variant>

#include "statmc/render/vec.h"

namespace statmc::render {

/// One sampled direction. `weight` = f·|cos θi| / pdf (what the path throughput is
/// multiplied by). For specular lobes `pdf` is the discrete probability of the lobe
/// chosen and takes no part in MIS.
struct BsdfSample {
    Vec3 wi;
    Rgb weight;
    float pdf = 0;
    bool specular = false;
    /// The factor by which `weight` scales radiance crossing a refracting boundary
    /// ((η_i/η_t)², 1 elsewhere): classic roulette factors it out, as pbrt-v3's etaScale does.
    float radiance_scale = 1;
};

/// Samples the cosine-weighted hemisphere around +z (pdf = cos θ / π).
Vec3 sample_cosine_hemisphere(float u1, float u2);

struct MatteLobe {
    Rgb kd;
    Rgb f(Vec3 wo, Vec3 wi) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    std::optional<BsdfSample> sample(Vec3 wo, float u1, float u2, float uc) const;
    Rgb albedo() const { return kd; }
    static constexpr bool kSpecular = false;
};

/// Rough conductor: Trowbridge-Reitz (GGX) microfacets, anisotropic alphas, the
/// height-correlated Smith masking term and the exact unpolarised conductor Fresnel term
/// with RGB eta and k; directions sampled from the distribution of visible normals.
struct MetalLobe {
    Rgb eta, k;
    float alpha_u, alpha_v;
    Rgb f(Vec3 wo, Vec3 wi) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    std::optional<BsdfSample> sample(Vec3 wo, float u1, float u2, float uc) const;
    Rgb albedo() const;
    static constexpr bool kSpecular = false;
};

/// Smooth dielectric (pbrt-v3 "glass" with zero roughness): Fresnel chooses reflection or
/// refraction; refracted radiance is scaled by (η_i/η_t)² as pbrt does in radiance mode.
struct GlassLobe {
    Rgb kr, kt;
    float ior;
    Rgb f(Vec3, Vec3) const { return {}; }
    float pdf(Vec3, Vec3) const { return 0; }
    std::optional<BsdfSample> sample(Vec3 wo, float u1, float u2, float uc) const;
    Rgb albedo() const { return kt; }
    static constexpr bool kSpecular = true;
};

/// Perfect specular reflection scaled by Kr.
struct MirrorLobe {
    Rgb kr;
    Rgb f(Vec3, Vec3) const { return {}; }
    float pdf(Vec3, Vec3) const { return 0; }
    std::optional<BsdfSample> sample(Vec3 wo, float u1, float u2, float uc) const;
    Rgb albedo() const { return kr; }
    static constexpr bool kSpecular = true;
};

/// Fresnel reflectance of a dielectric interface for cos θi (signed: negative means
/// arriving from inside) and relative index η = η_t/η_i of the outside→inside direction.
float fresnel_dielectric(float cos_i, float eta);
/// Fresnel reflectance of a conductor (per channel, unpolarised), outside medium η = 1.
Rgb fresnel_conductor(float cos_i, Rgb eta, Rgb k);

class Bsdf {
public:
    using Lobe = std::variant<MatteLobe, MetalLobe, GlassLobe, MirrorLobe>;

    /// `tangent` (dp/du, any length) orients the local s axis; zero picks any frame.
    Bsdf(Lobe lobe, Vec3 ns, Vec3 ng, Vec3 tangent = {})
        : lobe_(lobe), frame_(Frame::from_normal_tangent(ns, tangent)), ng_(ng)
    {
    }

    /// f(wo, wi) in world space, zero across the geometric surface for reflection lobes.
    Rgb f(Vec3 wo, Vec3 wi) const;
    float pdf(Vec3 wo, Vec3 wi) const;
    std::optional<BsdfSample> sample(Vec3 wo, float u1, float u2, float uc) const;
    /// Whether every lobe is a Dirac delta (then light sampling is pointless).
    bool is_specular() const;
    /// The reflectance the albedo guide records.
    Rgb albedo() const;
    Vec3 shading_normal() const { return frame_.n; }

private:
    Lobe lobe_;
    Frame frame_;
    Vec3 ng_;
};

}  // namespace statmc::render
