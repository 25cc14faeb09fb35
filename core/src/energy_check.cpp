#include "statmc/core/energy_check.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/thread_limit.h"

namespace statmc {

namespace {

/// Box sums of `in` (w × h, row-major) over the (2R + 1)² window around each pixel,
/// clipped to the image: a column pass, then a row pass, each adding its 2R + 1 terms in
/// the same order for every pixel, so that a sum depends on its window's values alone.
void box_sums(const std::vector<double>& in, int w, int h, int r, std::vector<double>& column,
              std::vector<double>& out)
{
    tbb::parallel_for(0, h, [&](int y) {
        const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
        double* row = column.data() + std::size_t(y) * w;
        for (int x = 0; x < w; ++x)
            row[x] = 0;
        for (int yy = y0; yy <= y1; ++yy) {
            const double* src = in.data() + std::size_t(yy) * w;
            for (int x = 0; x < w; ++x)
                row[x] += src[x];
        }
    });
    tbb::parallel_for(0, h, [&](int y) {
        const double* row = column.data() + std::size_t(y) * w;
        double* dst = out.data() + std::size_t(y) * w;
        for (int x = 0; x < w; ++x) {
            const int x0 = std::max(0, x - r), x1 = std::min(w - 1, x + r);
            double s = 0;
            for (int xx = x0; xx <= x1; ++xx)
                s += row[xx];
            dst[x] = s;
        }
    });
}

}  // namespace

std::size_t keep_window_energy(const StatisticsView& noisy, const std::vector<Plane>& out,
                               const EnergyCheckOptions& options, int nthreads)
{
    if (options.radius < 0)
        throw std::invalid_argument("energy check: radius must be >= 0");
    if (!(options.alpha > 0 && options.alpha < 1))
        throw std::invalid_argument("energy check: alpha must be in (0, 1)");
    if (options.radius == 0)
        return 0;
    if (!noisy.count || !noisy.has_variance())
        throw std::invalid_argument("energy check: needs the sample count and the variance");
    if (int(out.size()) < noisy.channels)
        throw std::invalid_argument("energy check: fewer output planes than channels");
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
                    const double o = out[c](x, y), m = noisy.mean[c](x, y);
                    const double n = noisy.count(x, y), s2 = noisy.variance[c](x, y);
                    const bool usable = n >= 2 && std::isfinite(m);
                    output[i] = std::isfinite(o) ? o : 0.0;
                    mean[i] = usable ? m : output[i];
                    const double v = noisy.variance_of_mean ? s2 : s2 / n;
                    variance[i] = usable && std::isfinite(v) && v > 0 ? v : 0.0;
                }
            });
            box_sums(mean, w, h, r, column, sum_mean);
            box_sums(output, w, h, r, column, sum_output);
            box_sums(variance, w, h, r, column, sum_variance);
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
            box_sums(excess, w, h, r, column, smoothed);
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
