#include "statmc/core/residual_check.h"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/thread_limit.h"
#include "window_sums.h"

namespace statmc {

std::size_t keep_window_residual(const StatisticsView& noisy, const std::vector<Plane>& out,
                                 const ResidualCheckOptions& options, int nthreads)
{
    if (!detail::window_check_runs("residual check", noisy, out, options.radius, options.alpha))
        return 0;
    const int w = noisy.width, h = noisy.height, r = options.radius;
    const std::size_t pixels = std::size_t(w) * h;
    const double z = normal_critical_value(options.alpha);
    const double window = double(2 * r + 1) * (2 * r + 1);
    // Per pixel: the residual out − x̄, its square, s²/n and its square; then their sums.
    std::vector<double> residual(pixels), square(pixels), variance(pixels), variance2(pixels);
    std::vector<double> sum_square(pixels), sum_variance(pixels), sum_variance2(pixels);
    std::vector<double> column(pixels);
    std::size_t off = 0;
    run_with_threads(nthreads, [&] {
        for (int c = 0; c < noisy.channels; ++c) {
            tbb::parallel_for(0, h, [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    const double o = out[c](x, y);
                    const bool usable = detail::usable_mean(noisy, c, x, y) && std::isfinite(o);
                    residual[i] = usable ? o - noisy.mean[c](x, y) : 0.0;
                    square[i] = residual[i] * residual[i];
                    variance[i] = usable ? detail::variance_of_mean(noisy, c, x, y) : 0.0;
                    variance2[i] = variance[i] * variance[i];
                }
            });
            detail::box_sums(square, w, h, r, column, sum_square);
            detail::box_sums(variance, w, h, r, column, sum_variance);
            detail::box_sums(variance2, w, h, r, column, sum_variance2);
            // Each window's share of its residual to give back where its test finds it
            // off, and that share's box mean (in buffers whose sums are read by then).
            std::vector<double>& share = square;
            std::vector<double>& smoothed = sum_variance2;
            off += tbb::parallel_reduce(
                tbb::blocked_range<int>(0, h), std::size_t(0),
                [&](const tbb::blocked_range<int>& rows, std::size_t found) {
                    for (int y = rows.begin(); y < rows.end(); ++y)
                        for (int x = 0; x < w; ++x) {
                            const std::size_t i = std::size_t(y) * w + x;
                            const double d = sum_square[i], v = sum_variance[i];
                            const bool too_large = d > v + z * std::sqrt(2 * sum_variance2[i]);
                            found += too_large;
                            share[i] = too_large ? 1 - v / d : 0.0;
                        }
                    return found;
                },
                [](std::size_t a, std::size_t b) { return a + b; });
            detail::box_sums(share, w, h, r, column, smoothed);
            tbb::parallel_for(0, h, [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    const double g = smoothed[i] / window;
                    if (g > 0 && residual[i] != 0)
                        out[c](x, y) = float(out[c](x, y) - g * residual[i]);
                }
            });
        }
    });
    return off;
}

}  // namespace statmc
