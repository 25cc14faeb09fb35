// The residual check (docs/method.md §17): the default method's last step, after the
// energy check. Where a denoise is right, what it took out of a window (the residual
// x̄ − out) is the noisy means' noise: its squares sum to about Σ s²/n. Where they sum to
// far more than that noise explains (a normal test at level α), the filter averaged
// pixels whose expectations differ; the window's output is pulled back towards the noisy
// means by the share that the squared-error estimate (SURE without its self-weight term)
// says is too much, smoothed over the same window so that no seam is drawn at the test's
// edge.
#pragma once

#include <cstddef>
#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

struct ResidualCheckOptions {
    int radius = 0;        ///< half width R of the (2R + 1)² window; 0 = off
    double alpha = 0.005;  ///< the test's level, in (0, 1); z at 1 − α/2, as the ladder's
};

/// How far the check reads and writes around a pixel: the window, then the smoothing.
inline int residual_check_reach(const ResidualCheckOptions& o) { return 2 * o.radius; }

/// Pulls `out` (a denoise of `noisy`'s means, `noisy.channels` planes) back towards x̄
/// where a window's residuals are larger than the noisy means' noise: per channel, with
/// D = Σ (out − x̄)², V = Σ s²/n and Q = Σ (s²/n)² over the window, a window is off where
/// D > V + z·sqrt(2Q) (the normal approximation of the sum of squares of normal errors of
/// the stated variances), and its share 1 − V/D is averaged over the (2R + 1)² box around
/// each pixel, zeros outside the image counted; the pixel's output becomes
/// out − share·(out − x̄). A pixel with n < 2 or a non-finite mean lends x̄ = its output and
/// no variance and is not moved; every pixel whose share is 0 keeps its bits. Needs the
/// untransformed variance (noisy.has_variance()). Returns the number of windows (pixel and
/// channel) that the test found off. Bitwise identical for any thread count, and at a pixel
/// it depends only on `out` within 2R of it. Throws std::invalid_argument for bad options,
/// missing planes or too few output planes.
std::size_t keep_window_residual(const StatisticsView& noisy, const std::vector<Plane>& out,
                                 const ResidualCheckOptions& options, int nthreads = 0);

}  // namespace statmc
