#include "statmc/core/harm_guard.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "statmc/core/thread_limit.h"
#include "statmc/core/variance_interval.h"

namespace statmc {

std::size_t keep_within_own_interval(const StatisticsView& stats, const Guides& guides,
                                     const std::vector<Plane>& out, const HarmGuardOptions& options,
                                     int nthreads)
{
    if (!(options.alpha > 0 && options.alpha < 1))
        throw std::invalid_argument("do-no-harm guard: alpha must be in (0, 1)");
    if (int(out.size()) < stats.channels)
        throw std::invalid_argument("do-no-harm guard: fewer output planes than channels");
    const std::vector<float> variance =
        denoise_variances(stats, TestDomain::Untransformed, guides, options.variance, nthreads);
    const double z = normal_critical_value(options.alpha);
    const std::size_t pixels = std::size_t(stats.width) * stats.height;
    std::atomic<std::size_t> changed{0};
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, stats.height, [&](int y) {
            std::size_t row_changed = 0;
            for (int x = 0; x < stats.width; ++x) {
                const double n = stats.count(x, y);
                if (!(n >= 2))
                    continue;
                for (int c = 0; c < stats.channels; ++c) {
                    const double v = variance[c * pixels + std::size_t(y) * stats.width + x];
                    const double mean = stats.mean[c](x, y);
                    const double half = z * std::sqrt(std::max(v, 0.0) / n);
                    float& value = out[c](x, y);
                    const float kept = float(std::clamp(double(value), mean - half, mean + half));
                    row_changed += kept != value;
                    value = kept;
                }
            }
            changed += row_changed;
        });
    });
    return changed.load();
}

}  // namespace statmc
