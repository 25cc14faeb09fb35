#include "statmc/render/russian_roulette.h"

#include <algorithm>
#include <cmath>

namespace statmc::render {

float classic_survival(const Rgb& beta)
{
    const float m = beta.max_component();
    if (!(m < 1.f))  // pbrt-v3's rrThreshold: no roulette at full throughput
        return 1.f;
    return 1.f - std::max(0.05f, 1.f - m);
}

std::optional<float> acrr_survival(float beta_max, float next_estimate, float pixel_estimate)
{
    if (!std::isfinite(pixel_estimate) || !(pixel_estimate > 0) || !std::isfinite(next_estimate) ||
        next_estimate < 0 || !(beta_max >= 0))
        return std::nullopt;
    const float s = beta_max * next_estimate / pixel_estimate;  // may be +inf: survive
    if (s >= 1.f)
        return 1.f;
    return std::max(kMinSurvival, std::min(s, 0.95f));
}

}  // namespace statmc::render
