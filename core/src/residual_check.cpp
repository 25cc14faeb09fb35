#include "statmc/core/residual_check.h"

#include <cmath>

#include "statmc/core/thread_limit.h"
#include "window_sums.h"

namespace statmc {

std::size_t keep_window_residual(const StatisticsView& noisy, const std::vector<Plane>& out,
                                 const ResidualCheckOptions& options, int nthreads)
{
    if (!detail::window_check_runs("residual check", noisy, out, options.radius, options.alpha))
        return 0;
    const detail::Windows win = detail::windows_of(noisy, options.radius, options.alpha);
    // Per pixel: the residual out − x̄, its square, s²/n and its square; then their sums.
    std::vector<double> residual(win.pixels), square(win.pixels), variance(win.pixels);
    std::vector<double> variance2(win.pixels), sum_square(win.pixels), sum_variance(win.pixels);
    std::vector<double> sum_variance2(win.pixels), column(win.pixels);
    std::size_t off = 0;
    run_with_threads(nthreads, [&] {
        for (int c = 0; c < noisy.channels; ++c) {
            detail::for_each_pixel(win, [&](std::size_t i, int x, int y) {
                const double o = out[c](x, y);
                const bool usable = detail::usable_mean(noisy, c, x, y) && std::isfinite(o);
                residual[i] = usable ? o - noisy.mean[c](x, y) : 0.0;
                square[i] = residual[i] * residual[i];
                variance[i] = usable ? detail::variance_of_mean(noisy, c, x, y) : 0.0;
                variance2[i] = variance[i] * variance[i];
            });
            detail::box_sums(square, win, column, sum_square);
            detail::box_sums(variance, win, column, sum_variance);
            detail::box_sums(variance2, win, column, sum_variance2);
            // Each window's share of its residual to give back where its test finds it
            // off, and that share's box mean (in buffers whose sums are read by then).
            std::vector<double>& share = square;
            std::vector<double>& smoothed = sum_variance2;
            off += detail::count_pixels(win, [&](std::size_t i) {
                const double d = sum_square[i], v = sum_variance[i];
                const bool too_large = d > v + win.z * std::sqrt(2 * sum_variance2[i]);
                share[i] = too_large ? 1 - v / d : 0.0;
                return too_large;
            });
            detail::box_sums(share, win, column, smoothed);
            detail::for_each_pixel(win, [&](std::size_t i, int x, int y) {
                const double g = smoothed[i] / win.area;
                if (g > 0 && residual[i] != 0)
                    out[c](x, y) = float(out[c](x, y) - g * residual[i]);
            });
        }
    });
    return off;
}

}  // namespace statmc
