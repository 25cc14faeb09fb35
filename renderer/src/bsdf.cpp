#include "statmc/render/bsdf.h"

#include <cmath>

namespace statmc::render {

Vec3 sample_cosine_hemisphere(float u1, float u2)
{
    // Shirley-Chiu concentric map of the square to the disk, lifted to the hemisphere.
    const float a = 2 * u1 - 1, b = 2 * u2 - 1;
    float r = 0, phi = 0;
    if (a != 0 || b != 0) {
        if (std::abs(a) > std::abs(b)) {
            r = a;
            phi = (kPi / 4) * (b / a);
        } else {
            r = b;
            phi = kPi / 2 - (kPi / 4) * (a / b);
        }
    }
    const float x = r * std::cos(phi), y = r * std::sin(phi);
    return {x, y, std::sqrt(std::max(0.f, 1 - x * x - y * y))};
}

float fresnel_dielectric(float cos_i, float eta)
{
    cos_i = std::clamp(cos_i, -1.f, 1.f);
    if (cos_i < 0) {  // from inside: swap the media
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    const float sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1)
        return 1;  // total internal reflection
    const float cos_t = std::sqrt(1 - sin2_t);
    const float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

Rgb fresnel_conductor(float cos_i, Rgb eta, Rgb k)
{
    cos_i = std::clamp(std::abs(cos_i), 0.f, 1.f);
    const float cos2 = cos_i * cos_i, sin2 = 1 - cos2;
    Rgb out;
    for (int c = 0; c < 3; ++c) {
        const float e2 = eta[c] * eta[c], k2 = k[c] * k[c];
        const float t0 = e2 - k2 - sin2;
        const float a2b2 = std::sqrt(std::max(0.f, t0 * t0 + 4 * e2 * k2));
        const float a = std::sqrt(std::max(0.f, 0.5f * (a2b2 + t0)));
        const float t1 = a2b2 + cos2, t2 = 2 * a * cos_i;
        const float rs = (t1 - t2) / (t1 + t2);
        const float t3 = cos2 * a2b2 + sin2 * sin2, t4 = t2 * sin2;
        const float rp = rs * (t3 - t4) / (t3 + t4);
        out[c] = 0.5f * (rp + rs);
    }
    return out;
}

Rgb Bsdf::f(Vec3 wo, Vec3 wi) const
{
    // pbrt's rule against light leaks through shading normals: a reflection lobe only
    // connects directions on the same side of the geometric surface.
    if (dot(wo, ng_) * dot(wi, ng_) <= 0)
        return {};
    const Vec3 lo = frame_.to_local(wo), li = frame_.to_local(wi);
    return std::visit([&](const auto& lobe) { return lobe.f(lo, li); }, lobe_);
}

float Bsdf::pdf(Vec3 wo, Vec3 wi) const
{
    const Vec3 lo = frame_.to_local(wo), li = frame_.to_local(wi);
    return std::visit([&](const auto& lobe) { return lobe.pdf(lo, li); }, lobe_);
}

std::optional<BsdfSample> Bsdf::sample(Vec3 wo, float u1, float u2, float uc) const
{
    const Vec3 lo = frame_.to_local(wo);
    auto s = std::visit([&](const auto& lobe) { return lobe.sample(lo, u1, u2, uc); }, lobe_);
    if (!s)
        return s;
    s->wi = frame_.to_world(s->wi);
    if (!s->specular && dot(wo, ng_) * dot(s->wi, ng_) <= 0)
        return std::nullopt;
    return s;
}

bool Bsdf::is_specular() const
{
    return std::visit([](const auto& lobe) { return std::decay_t<decltype(lobe)>::kSpecular; },
                      lobe_);
}

Rgb Bsdf::albedo() const
{
    return std::visit([](const auto& lobe) { return lobe.albedo(); }, lobe_);
}

}  // namespace statmc::render
