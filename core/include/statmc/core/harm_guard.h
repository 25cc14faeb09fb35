// The do-no-harm rule (docs/method.md §11): no output pixel may end up statistically
// inconsistent with its own unbiased estimate. Whatever the filter did, each output value
// is pulled back into the confidence interval of the pixel's own mean,
//
//     |out − x̄| ≤ z · sqrt(ṽ / n),   z at 1 − α/2,
//
// with ṽ a denoised per-sample variance in linear units (variance_filter.h, borrowing for
// pixels without an interval), since a pixel's own s² is too noisy at low sample counts:
// a dark speckle (all samples 0, s² = 0) would keep the filter from ever lifting it.
#pragma once

#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"
#include "statmc/core/variance_filter.h"

namespace statmc {

struct HarmGuardOptions {
    /// The guard's significance: a filter whose output equals the true mean is cut back
    /// at about this rate per pixel and channel (the normal approximation of x̄). In (0, 1).
    double alpha = 0.005;
    /// How ṽ is estimated from the untransformed variance and its moments.
    VarianceFilterOptions variance{3, 0.05, 2.f, 0.02f, 0.1f, true};
};

/// Clamps each channel of `out` (the filter's output over `stats`' pixels) into
/// x̄ ± z·sqrt(ṽ/n), ṽ denoised with `guides` (as the variance filter takes them). `stats` needs the
/// untransformed variance with M3 and M4 (stats.has_moments()); a pixel with n < 2 is left as it
/// is. Returns the number of values it changed. Deterministic for any `nthreads` (0 = all cores).
/// Throws std::invalid_argument for bad options or missing planes.
std::size_t keep_within_own_interval(const StatisticsView& stats, const Guides& guides,
                                     const std::vector<Plane>& out,
                                     const HarmGuardOptions& options = {}, int nthreads = 0);

}  // namespace statmc
