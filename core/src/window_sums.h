// What the energy and residual checks share: their inputs per pixel, their validation and
// their sums over windows.
#pragma once

#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc::detail {

/// Validates a window check's options and planes, throwing std::invalid_argument that
/// names `check`; false when `radius` is 0 (the check is off and reads nothing).
bool window_check_runs(const char* check, const StatisticsView& noisy,
                       const std::vector<Plane>& out, int radius, double alpha);

/// Whether the pixel's mean can be checked against: n ≥ 2 and a finite mean.
bool usable_mean(const StatisticsView& noisy, int c, int x, int y);

/// The variance of the pixel's mean, s²/n (or the stored one, with variance_of_mean);
/// 0 where it is not finite and positive.
double variance_of_mean(const StatisticsView& noisy, int c, int x, int y);

/// Box sums of `in` (w × h, row-major) over the (2R + 1)² window around each pixel,
/// clipped to the image: a column pass, then a row pass, each adding its 2R + 1 terms in
/// the same order for every pixel, so that a sum depends on its window's values alone.
/// `column` is scratch of w × h. Call inside the caller's thread limit.
void box_sums(const std::vector<double>& in, int w, int h, int r, std::vector<double>& column,
              std::vector<double>& out);

}  // namespace statmc::detail
