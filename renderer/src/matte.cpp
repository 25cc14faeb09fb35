// pbrt-v3 "matte" with sigma = 0: a Lambertian reflector, two-sided as pbrt's BxDFs are
// (they work in the hemisphere of wo, whichever side that is).
#include <cmath>

#include "statmc/render/bsdf.h"

namespace statmc::render {

Rgb MatteLobe::f(Vec3 wo, Vec3 wi) const { return wo.z * wi.z > 0 ? kd * kInvPi : Rgb{}; }

float MatteLobe::pdf(Vec3 wo, Vec3 wi) const
{
    return wo.z * wi.z > 0 ? std::abs(wi.z) * kInvPi : 0.f;
}

std::optional<BsdfSample> MatteLobe::sample(Vec3 wo, float u1, float u2, float) const
{
    if (wo.z == 0)
        return std::nullopt;
    Vec3 wi = sample_cosine_hemisphere(u1, u2);
    if (wo.z < 0)
        wi.z = -wi.z;
    const float p = pdf(wo, wi);
    if (p <= 0)
        return std::nullopt;
    return BsdfSample{wi, kd, p, false};  // f·cos/pdf = kd exactly
}

}  // namespace statmc::render
