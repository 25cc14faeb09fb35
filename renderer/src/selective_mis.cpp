#include "statmc/render/selective_mis.h"

#include <cmath>

namespace statmc::render {

TechniqueChoice choose_techniques(float light_wins, float bsdf_wins, float threshold)
{
    TechniqueChoice choice;
    if (!std::isfinite(light_wins) || !std::isfinite(bsdf_wins) || light_wins < 0 || bsdf_wins < 0)
        return choice;
    const double sum = double(light_wins) + double(bsdf_wins);
    if (!(sum > 0))
        return choice;
    choice.light = !(light_wins / sum < threshold);
    choice.bsdf = !(bsdf_wins / sum < threshold);
    if (!choice.light && !choice.bsdf)  // only for an invalid threshold ≥ 0.5; stay unbiased
        choice = {};
    return choice;
}

}  // namespace statmc::render
