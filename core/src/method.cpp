#include "statmc/core/method.h"

namespace statmc {

MethodSettings method_settings(Method method)
{
    MethodSettings s;
    switch (method) {
    case Method::Default:
        s.stages.radius_ladder = true;
        s.stages.ladder.alpha = 0.005;
        // Its intervals read variances moderated (d0 = 16, docs/method.md §10) towards the
        // neighbours whose means agree, more where heavy tails make a pixel's s² unsure.
        s.stages.ladder.variance.prior_dof = 16;
        s.stages.ladder.variance.prior_alpha = 0.05;
        s.stages.ladder.variance.own_dof_from_scatter = true;
        s.stages.context_radius = 1;
        // Windows of the moderation's size, tested at the ladder's level (§16, §17).
        s.stages.ladder.energy = {s.stages.ladder.variance.radius, s.stages.ladder.alpha};
        s.stages.ladder.residual = {s.stages.ladder.variance.radius, s.stages.ladder.alpha};
        break;
    case Method::Classic:
        s.filter.guide_noise = false;
        break;
    case Method::Paper:
        s.filter = DenoiseOptions::paper();
        break;
    }
    return s;
}

}  // namespace statmc
