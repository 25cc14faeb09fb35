#include "statmc/core/energy_check.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/thread_limit.h"
#include "window_sums.h"

namespace statmc {

std::size_t keep_window_energy(const StatisticsView& noisy, const std::vector<Plane>& out,
                               const EnergyCheckOptions& options, int nthreads)
{
    if (!detail::window_check_runs("energy check", noisy, out, options.radius, options.alpha))
        return 0;
    const int w = noisy.width, h = noisy.height, r = options.radius;
    const std::size_t pixels = std::size_t(w) * h;
    const double z = normal_critical_value(options.alpha);
    const double window = double(2 * r + 1) * (2 * r + 1);
    std::vector<double> mean(pixels), output(pixels), variance(pixels), column(pixels);
    std::vector<double> sum_mean(pixels), sum_output(pixels), sum_variance(pixels);
    std::size_t off = 0;
    run_with_threads(nthreads, [&] {
        for (int c = 0; c < noisy.channels; ++c) {
            tbb::parallel_for(0, h, [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    const double o = out[c](x, y);
                    const bool usable = detail::usable_mean(noisy, c, x, y);
                    output[i] = std::isfinite(o) ? o : 0.0;
                    mean[i] = usable ? double(noisy.mean[c](x, y)) : output[i];
                    variance[i] = usable ? detail::variance_of_mean(noisy, c, x, y) : 0.0;
                }
            });
            detail::box_sums(mean, w, h, r, column, sum_mean);
            detail::box_sums(output, w, h, r, column, sum_output);
            detail::box_sums(variance, w, h, r, column, sum_variance);
            // Each window's factor less 1 where its test finds it off, and its box mean
            // (in buffers whose sums are read by then).
            std::vector<double>& excess = variance;
            std::vector<double>& smoothed = sum_variance;
            off += tbb::parallel_reduce(
                tbb::blocked_range<int>(0, h), std::size_t(0),
                [&](const tbb::blocked_range<int>& rows, std::size_t found) {
                    for (int y = rows.begin(); y < rows.end(); ++y)
                        for (int x = 0; x < w; ++x) {
                            const std::size_t i = std::size_t(y) * w + x;
                            const double a = sum_mean[i], b = sum_output[i];
                            const bool moved = std::abs(a - b) > z * std::sqrt(sum_variance[i]);
                            found += moved;
                            excess[i] =
                                moved && a > 0 && b > 0
                                    ? std::clamp(a / b, 1 / kMaxEnergyFactor, kMaxEnergyFactor) - 1
                                    : 0.0;
                        }
                    return found;
                },
                [](std::size_t a, std::size_t b) { return a + b; });
            detail::box_sums(excess, w, h, r, column, smoothed);
            // Only a pixel that moved the way its windows' light did (down where they lost
            // light, up where they invented it) is scaled back; one that moved the other way
            // took the light that went missing elsewhere, and scaling it would add to that.
            // A pixel without a usable mean lent its output as its mean, so it moved neither.
            tbb::parallel_for(0, h, [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    const double g = smoothed[i] / window;
                    if (g != 0 && (g > 0 ? output[i] < mean[i] : output[i] > mean[i]))
                        out[c](x, y) = float(out[c](x, y) * (1 + g));
                }
            });
        }
    });
    return off;
}

}  // namespace statmc
