// What the energy and residual checks share: their inputs per pixel, their validation and
// their sums over windows.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc::detail {

/// Validates a window check's options and planes, throwing std::invalid_argument that
/// names `check`; false when `radius` is 0 (the check is off and reads nothing).
bool window_check_runs(const char* check, const StatisticsView& noisy,
                       const std::vector<Plane>& out, int radius, double alpha);

/// The windows a check tests: the image's size, their half width R, their area (2R + 1)²
/// and the test's critical value z at 1 − α/2.
struct Windows {
    int w = 0, h = 0, r = 0;
    std::size_t pixels = 0;
    double area = 0, z = 0;
};
Windows windows_of(const StatisticsView& noisy, int radius, double alpha);

/// Calls f(i, x, y) for every pixel, i = y·w + x, rows in parallel.
template <class F>
void for_each_pixel(const Windows& win, F&& f)
{
    tbb::parallel_for(0, win.h, [&](int y) {
        for (int x = 0; x < win.w; ++x)
            f(std::size_t(y) * win.w + x, x, y);
    });
}

/// How many pixels `off(i)` is true for, calling it once for every pixel, rows in parallel.
template <class F>
std::size_t count_pixels(const Windows& win, F&& off)
{
    return tbb::parallel_reduce(
        tbb::blocked_range<int>(0, win.h), std::size_t(0),
        [&](const tbb::blocked_range<int>& rows, std::size_t found) {
            for (int y = rows.begin(); y < rows.end(); ++y)
                for (int x = 0; x < win.w; ++x)
                    found += off(std::size_t(y) * win.w + x) ? 1 : 0;
            return found;
        },
        [](std::size_t a, std::size_t b) { return a + b; });
}

/// Whether the pixel's mean can be checked against: n ≥ 2 and a finite mean. (Inline:
/// both checks call these once per pixel and channel.)
inline bool usable_mean(const StatisticsView& noisy, int c, int x, int y)
{
    return noisy.count(x, y) >= 2 && std::isfinite(noisy.mean[c](x, y));
}

/// The variance of the pixel's mean, s²/n (or the stored one, with variance_of_mean);
/// 0 where it is not finite and positive.
inline double variance_of_mean(const StatisticsView& noisy, int c, int x, int y)
{
    const double s2 = noisy.variance[c](x, y);
    const double v = noisy.variance_of_mean ? s2 : s2 / noisy.count(x, y);
    return std::isfinite(v) && v > 0 ? v : 0.0;
}

/// The planes the checks read (count, and each channel's mean and variance; those the view
/// lacks stay missing) copied into `storage` as dense planes (dense_copies.h), and a view
/// of them, without Box-Cox or higher moments: each check reads them channel by channel,
/// and an image's own planes interleave all of its layers. Same values, bit for bit. Call
/// inside the caller's thread limit.
StatisticsView dense_check_inputs(const StatisticsView& noisy, std::vector<float>& storage);

/// Box sums of `in` (w × h, row-major) over the (2R + 1)² window around each pixel,
/// clipped to the image: a column pass, then a row pass, each adding its 2R + 1 terms in
/// the same order for every pixel, so that a sum depends on its window's values alone.
/// `column` is scratch of w × h. Call inside the caller's thread limit.
void box_sums(const std::vector<double>& in, const Windows& win, std::vector<double>& column,
              std::vector<double>& out);

}  // namespace statmc::detail
