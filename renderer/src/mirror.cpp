// pbrt-v3 "mirror": perfect specular reflection with reflectance Kr (default 0.9).
#include "statmc/render/bsdf.h"

namespace statmc::render {

std::optional<BsdfSample> MirrorLobe::sample(Vec3 wo, float, float, float) const
{
    if (wo.z == 0)
        return std::nullopt;
    return BsdfSample{{-wo.x, -wo.y, wo.z}, kr, 1.f, true};
}

}  // namespace statmc::render
