// pbrt-v3 "metal": a microfacet conductor. D is Trowbridge-Reitz (GGX) with alphas
// (αu, αv) along the frame's s and t axes, G is the height-correlated Smith term
// 1/(1 + Λ(wo) + Λ(wi)), F the conductor Fresnel term at the microfacet. Directions come
// from the visible-normal distribution (Heitz 2018), so the pdf is
// G1(wo)·D(wh)/(4·cos θo) and the sample weight F·G/G1(wo).
#include <cmath>

#include "statmc/render/bsdf.h"

namespace statmc::render {

namespace {

float ggx_d(Vec3 wh, float ax, float ay)
{
    if (wh.z <= 0)
        return 0;
    const float x = wh.x / ax, y = wh.y / ay;
    const float t = x * x + y * y + wh.z * wh.z;
    return 1.f / (kPi * ax * ay * t * t);
}

float smith_lambda(Vec3 w, float ax, float ay)
{
    if (w.z == 0)
        return 1e30f;
    const float a2t2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / (w.z * w.z);
    return 0.5f * (-1.f + std::sqrt(1.f + a2t2));
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals"; wo.z > 0.
Vec3 sample_visible_normal(Vec3 wo, float ax, float ay, float u1, float u2)
{
    const Vec3 vh = normalize({ax * wo.x, ay * wo.y, wo.z});
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len2 > 0 ? Vec3{-vh.y, vh.x, 0} / std::sqrt(len2) : Vec3{1, 0, 0};
    const Vec3 t2 = cross(vh, t1);
    const float r = std::sqrt(u1), phi = 2 * kPi * u2;
    const float p1 = r * std::cos(phi);
    float p2 = r * std::sin(phi);
    const float s = 0.5f * (1 + vh.z);
    p2 = (1 - s) * std::sqrt(std::max(0.f, 1 - p1 * p1)) + s * p2;
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.f, 1 - p1 * p1 - p2 * p2));
    return normalize({ax * nh.x, ay * nh.y, std::max(1e-6f, nh.z)});
}

// The lobe is two-sided like pbrt's BxDFs: work in the hemisphere of wo.
void to_upper(Vec3& wo, Vec3& wi)
{
    if (wo.z < 0) {
        wo.z = -wo.z;
        wi.z = -wi.z;
    }
}

}  // namespace

Rgb MetalLobe::f(Vec3 wo, Vec3 wi) const
{
    to_upper(wo, wi);
    if (wo.z <= 0 || wi.z <= 0)
        return {};
    const Vec3 wh = normalize(wo + wi);
    const float g =
        1.f / (1.f + smith_lambda(wo, alpha_u, alpha_v) + smith_lambda(wi, alpha_u, alpha_v));
    const Rgb F = fresnel_conductor(dot(wi, wh), eta, k);
    return F * (ggx_d(wh, alpha_u, alpha_v) * g / (4 * wo.z * wi.z));
}

float MetalLobe::pdf(Vec3 wo, Vec3 wi) const
{
    to_upper(wo, wi);
    if (wo.z <= 0 || wi.z <= 0)
        return 0;
    const Vec3 wh = normalize(wo + wi);
    const float g1 = 1.f / (1.f + smith_lambda(wo, alpha_u, alpha_v));
    return g1 * ggx_d(wh, alpha_u, alpha_v) / (4 * wo.z);
}

std::optional<BsdfSample> MetalLobe::sample(Vec3 wo, float u1, float u2, float) const
{
    const bool flipped = wo.z < 0;
    Vec3 o = wo;
    if (flipped)
        o.z = -o.z;
    if (o.z <= 0)
        return std::nullopt;
    const Vec3 wh = sample_visible_normal(o, alpha_u, alpha_v, u1, u2);
    const float cos_oh = dot(o, wh);
    Vec3 wi = wh * (2 * cos_oh) - o;
    if (wi.z <= 0 || cos_oh <= 0)
        return std::nullopt;
    const float lo = smith_lambda(o, alpha_u, alpha_v), li = smith_lambda(wi, alpha_u, alpha_v);
    const float g1 = 1.f / (1.f + lo);
    const float pdf = g1 * ggx_d(wh, alpha_u, alpha_v) / (4 * o.z);
    if (!(pdf > 0))
        return std::nullopt;
    const Rgb weight = fresnel_conductor(cos_oh, eta, k) * ((1.f + lo) / (1.f + lo + li));
    if (flipped)
        wi.z = -wi.z;
    return BsdfSample{wi, weight, pdf, false};
}

Rgb MetalLobe::albedo() const { return fresnel_conductor(1.f, eta, k); }

}  // namespace statmc::render
