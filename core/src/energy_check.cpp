#include "statmc/core/energy_check.h"

#include <algorithm>
#include <cmath>

#include "statmc/core/thread_limit.h"
#include "window_sums.h"

namespace statmc {

std::size_t keep_window_energy(const StatisticsView& noisy, const std::vector<Plane>& out,
                               const EnergyCheckOptions& options, int nthreads)
{
    if (!detail::window_check_runs("energy check", noisy, out, options.radius, options.alpha))
        return 0;
    const detail::Windows win = detail::windows_of(noisy, options.radius, options.alpha);
    std::vector<double> mean(win.pixels), output(win.pixels), variance(win.pixels);
    std::vector<double> sum_mean(win.pixels), sum_output(win.pixels), sum_variance(win.pixels);
    std::vector<double> column(win.pixels);
    std::size_t off = 0;
    run_with_threads(nthreads, [&] {
        for (int c = 0; c < noisy.channels; ++c) {
            detail::for_each_pixel(win, [&](std::size_t i, int x, int y) {
                const double o = out[c](x, y);
                const bool usable = detail::usable_mean(noisy, c, x, y);
                output[i] = std::isfinite(o) ? o : 0.0;
                mean[i] = usable ? double(noisy.mean[c](x, y)) : output[i];
                variance[i] = usable ? detail::variance_of_mean(noisy, c, x, y) : 0.0;
            });
            detail::box_sums(mean, win, column, sum_mean);
            detail::box_sums(output, win, column, sum_output);
            detail::box_sums(variance, win, column, sum_variance);
            // Each window's factor less 1 where its test finds it off, and its box mean
            // (in buffers whose sums are read by then).
            std::vector<double>& excess = variance;
            std::vector<double>& smoothed = sum_variance;
            off += detail::count_pixels(win, [&](std::size_t i) {
                const double a = sum_mean[i], b = sum_output[i];
                const bool moved = std::abs(a - b) > win.z * std::sqrt(sum_variance[i]);
                excess[i] = moved && a > 0 && b > 0
                                ? std::clamp(a / b, 1 / kMaxEnergyFactor, kMaxEnergyFactor) - 1
                                : 0.0;
                return moved;
            });
            detail::box_sums(excess, win, column, smoothed);
            // Only a pixel that moved the way its windows' light did (down where they lost
            // light, up where they invented it) is scaled back; one that moved the other way
            // took the light that went missing elsewhere, and scaling it would add to that.
            // A pixel without a usable mean lent its output as its mean, so it moved neither.
            detail::for_each_pixel(win, [&](std::size_t i, int x, int y) {
                const double g = smoothed[i] / win.area;
                if (g != 0 && (g > 0 ? output[i] < mean[i] : output[i] > mean[i]))
                    out[c](x, y) = float(out[c](x, y) * (1 + g));
            });
        }
    });
    return off;
}

}  // namespace statmc
