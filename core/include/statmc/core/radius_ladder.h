// A per-pixel choice of the filter radius by the intersection of confidence intervals
// (ICI, Katkovnik's rule; docs/method.md §11): the default method's way of keeping each
// output consistent with its own pixel, which drops a harmful average instead of clamping it. Each rung r of a ladder of
// radii gives the pixel an estimate ŷ_r (the filter at radius r; ŷ_0 = x̄) and an interval
// ŷ_r ± z·sqrt(ṽ / N_r), N_r the filter's effective sample count; the pixel takes the
// largest r whose interval still overlaps those of every smaller rung, in every channel.
#pragma once

#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/energy_check.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/residual_check.h"
#include "statmc/core/statistics_view.h"
#include "statmc/core/variance_filter.h"

namespace statmc {

struct RadiusLadderOptions {
    /// The rungs above 0, ascending; those above the filter's radius are dropped and the
    /// filter's radius is always the last rung.
    std::vector<int> radii = {1, 2, 3, 5, 8, 12, 20};
    double alpha = 0.005;  ///< of each rung's interval, in (0, 1)
    /// A pixel whose intervals stop it at a rung where every one of its 8-neighbours (those
    /// inside the image) goes on goes on too, its intersection restarting from that rung's
    /// interval: at α per rung and channel, a lone stop in a region that goes on is more
    /// often the test's false alarm than a one-pixel feature, which the membership test
    /// keeps anyway (docs/method.md §11). false: each pixel by its own intervals alone.
    bool overrule_lone_stops = true;
    /// How ṽ is estimated from the untransformed variance and its moments.
    VarianceFilterOptions variance{3, 0.05, 2.f, 0.02f, 0.1f, true};
    /// The energy check run on the result (energy_check.h); radius 0: none.
    EnergyCheckOptions energy;
    /// The residual check run after it (residual_check.h); radius 0: none.
    ResidualCheckOptions residual;
};

/// How far the ladder's checks read its output around a pixel: the energy check's reach,
/// then the residual check's on the energy check's output.
inline int checks_reach(const RadiusLadderOptions& ladder)
{
    return energy_check_reach(ladder.energy) + residual_check_reach(ladder.residual);
}

/// Filters `est` (built from `stats`) into `out`, each pixel at its ICI radius. `stats`
/// needs the untransformed variance, and M3 and M4 when `ladder.variance` tests intervals
/// (stats.has_moments()). `est` may hold channels beyond stats' (the context channel,
/// context_channel.h): they take part in the test, while the intervals and `out` are
/// stats' channels alone. Pixels with n < 2 keep their value. Bitwise identical for any
/// thread count. `wanted`: only those pixels (PixelMask); the walk and the intervals then
/// cover them and the pixels within one per rung of them, which the lone-stop rule reads,
/// and first those within the checks' reach of them (checks_reach), which they read. Throws
/// std::invalid_argument for bad options or missing planes.
void filter_with_radius_ladder(const StatisticsView& stats, const EstimatorImage& est,
                               const Guides& guides, const DenoiseOptions& options,
                               const std::vector<Plane>& out,
                               const RadiusLadderOptions& ladder = {}, int nthreads = 0,
                               const PixelMask& wanted = {});

}  // namespace statmc
