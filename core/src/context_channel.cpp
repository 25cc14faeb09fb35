#include "statmc/core/context_channel.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "statmc/core/firefly_guard.h"
#include "statmc/core/thread_limit.h"

namespace statmc {

EstimatorImage with_context(const EstimatorImage& est, int channel, int radius, float firefly_ratio,
                            int nthreads)
{
    if (est.channels >= kMaxEstimatorChannels)
        throw std::invalid_argument("context: the image has no room for another channel");
    if (channel < 0 || channel >= est.channels)
        throw std::invalid_argument("context: no channel " + std::to_string(channel));
    if (radius < 1)
        throw std::invalid_argument("context: the box radius must be >= 1");
    EstimatorImage out(est.width, est.height, est.channels + 1);
    out.domain = est.domain;
    out.context_channels = est.context_channels + 1;
    std::copy(est.count.begin(), est.count.end(), out.count.begin());
    std::copy(est.value.begin(), est.value.end(), out.value.begin());
    std::copy(est.test_mean.begin(), est.test_mean.end(), out.test_mean.begin());
    std::copy(est.test_variance.begin(), est.test_variance.end(), out.test_variance.begin());
    const int w = est.width, h = est.height, context = est.channels;
    run_with_threads(nthreads, [&] {
        // The firefly guard's view of the pixels: a box leaves out what its centre would not
        // accept, so that a firefly changes no other pixel's context; and the centre itself,
        // so that a firefly's own context is its surroundings'.
        const NoiseLevels noise = noise_levels(est, firefly_ratio);
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                double mean = 0, variance = 0, value = 0;
                int k = 0;
                for (int yy = std::max(y - radius, 0); yy <= std::min(y + radius, h - 1); ++yy)
                    for (int xx = std::max(x - radius, 0); xx <= std::min(x + radius, w - 1);
                         ++xx) {
                        const std::size_t q = std::size_t(yy) * w + xx;
                        if ((xx == x && yy == y) || !est.testable(xx, yy) ||
                            !(noise.level[q] <= noise.limit[std::size_t(y) * w + x]))
                            continue;
                        mean += est.test_mean[est.index(channel, xx, yy)];
                        variance += est.test_variance[est.index(channel, xx, yy)];
                        value += est.value[est.index(channel, xx, yy)];
                        ++k;
                    }
                const std::size_t to = out.index(context, x, y), from = est.index(channel, x, y);
                out.test_mean[to] = k ? float(mean / k) : est.test_mean[from];
                out.test_variance[to] =
                    k ? float(variance / (double(k) * k)) : est.test_variance[from];
                out.value[to] = k ? float(value / k) : est.value[from];
            }
        });
    });
    return out;
}

}  // namespace statmc
