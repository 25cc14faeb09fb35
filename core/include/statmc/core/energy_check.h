// The energy check (docs/method.md §16), run on the default method's radius ladder's result
// before the residual check (residual_check.h). A denoise may move light between pixels,
// but over a small window its output should hold the light the noisy means hold, which
// are unbiased. Where a window's two sums differ by more than the
// noise of the noisy sum explains (a normal test at level α), the filter has lost or
// invented light there; the pixels that moved that way are scaled back towards the noisy
// sum, by a factor smoothed over the same window so that no seam is drawn at the test's
// edge.
#pragma once

#include <cstddef>
#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

struct EnergyCheckOptions {
    int radius = 0;        ///< half width R of the (2R + 1)² window; 0 = off
    double alpha = 0.005;  ///< the test's two-sided level, in (0, 1)
};

/// Each window's factor is kept within [1/kMaxEnergyFactor, kMaxEnergyFactor]: a window
/// whose output sum is near 0 would otherwise give any factor at all.
constexpr double kMaxEnergyFactor = 4.0;

/// How far the check reads and writes around a pixel: the window, then the smoothing.
inline int energy_check_reach(const EnergyCheckOptions& o) { return 2 * o.radius; }

/// Scales `out` (a denoise of `noisy`'s means, `noisy.channels` planes) where a window's
/// light differs from the noisy means' by more than z·sqrt(Σ s²/n), z at 1 − α/2: per
/// channel, the factor Σ x̄ / Σ out of every such window (1 elsewhere, and where either sum
/// is not positive) is averaged over the (2R + 1)² box around each pixel, zeros outside
/// the image counted, and the pixel's output multiplied by it where the output moved from
/// x̄ the way the factor undoes (below x̄ for a factor above 1, above x̄ for one below). A
/// pixel with n < 2 or a non-finite mean lends x̄ = its output and no variance and is not
/// scaled; every pixel not scaled keeps its bits. Needs the untransformed variance
/// (noisy.has_variance()). Returns the number of windows (pixel and channel) that the test found
/// off. Bitwise identical for any thread count, and at a pixel it depends only on `out` within 2R
/// of it. Throws std::invalid_argument for bad options, missing planes or too few output planes.
std::size_t keep_window_energy(const StatisticsView& noisy, const std::vector<Plane>& out,
                               const EnergyCheckOptions& options, int nthreads = 0);

}  // namespace statmc
