// pbrt-v3 "glass" with zero roughness (FresnelSpecular): reflect with probability F,
// refract otherwise, so each branch's weight is Kr or Kt·(η_i/η_t)².
#include <cmath>

#include "statmc/render/bsdf.h"

namespace statmc::render {

std::optional<BsdfSample> GlassLobe::sample(Vec3 wo, float, float, float uc) const
{
    if (wo.z == 0)
        return std::nullopt;
    const float F = fresnel_dielectric(wo.z, ior);
    if (uc < F)
        return BsdfSample{{-wo.x, -wo.y, wo.z}, kr, F, true};
    // Refraction: entering when wo is on the outside (+z).
    const bool entering = wo.z > 0;
    const float eta_i = entering ? 1.f : ior, eta_t = entering ? ior : 1.f;
    const float eta = eta_i / eta_t;
    const float cos_i = std::abs(wo.z);
    const float sin2_t = eta * eta * std::max(0.f, 1 - cos_i * cos_i);
    if (sin2_t >= 1)
        return std::nullopt;  // cannot happen: F = 1 under total internal reflection
    const float cos_t = std::sqrt(1 - sin2_t);
    const Vec3 n = entering ? Vec3{0, 0, 1} : Vec3{0, 0, -1};
    const Vec3 wi = normalize(-wo * eta + n * (eta * cos_i - cos_t));
    return BsdfSample{wi, kt * (eta * eta), 1 - F, true, eta * eta};
}

}  // namespace statmc::render
