#include "statmc/core/context_channel.h"

#include <algorithm>
#include <cstdint>
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
    out.support = est.support;
    std::copy(est.value.begin(), est.value.end(), out.value.begin());
    std::copy(est.test_mean.begin(), est.test_mean.end(), out.test_mean.begin());
    std::copy(est.test_variance.begin(), est.test_variance.end(), out.test_variance.begin());
    const int w = est.width, h = est.height, context = est.channels;
    run_with_threads(nthreads, [&] {
        // The firefly guard's view of the pixels: a box leaves out what its centre would not
        // accept, so that a firefly changes no other pixel's context; and the centre itself,
        // so that a firefly's own context is its surroundings'.
        const NoiseLevels noise = noise_levels(est, firefly_ratio);
        // Whether each pixel is testable, once: every box would otherwise test it again.
        std::vector<std::uint8_t> testable(est.pixels());
        tbb::parallel_for(
            0, h, [&](int y) { est.testable_row(y, testable.data() + std::size_t(y) * w); });
        const float* test_mean = est.test_mean.data() + est.index(channel, 0, 0);
        const float* test_variance = est.test_variance.data() + est.index(channel, 0, 0);
        const float* value_plane = est.value.data() + est.index(channel, 0, 0);
        tbb::parallel_for(0, h, [&](int y) {
            const int y0 = std::max(y - radius, 0), y1 = std::min(y + radius, h - 1);
            for (int x = 0; x < w; ++x) {
                const std::size_t centre = std::size_t(y) * w + x;
                const float limit = noise.limit[centre];
                const int x0 = std::max(x - radius, 0), x1 = std::min(x + radius, w - 1);
                double mean = 0, variance = 0, value = 0;
                int k = 0;
                for (int yy = y0; yy <= y1; ++yy)
                    for (std::size_t q = std::size_t(yy) * w + x0, end = q + (x1 - x0); q <= end;
                         ++q) {
                        if (q == centre || !testable[q] || !(noise.level[q] <= limit))
                            continue;
                        mean += test_mean[q];
                        variance += test_variance[q];
                        value += value_plane[q];
                        ++k;
                    }
                const std::size_t to = out.index(context, x, y);
                out.test_mean[to] = k ? float(mean / k) : test_mean[centre];
                out.test_variance[to] =
                    k ? float(variance / (double(k) * k)) : test_variance[centre];
                out.value[to] = k ? float(value / k) : value_plane[centre];
            }
        });
    });
    return out;
}

}  // namespace statmc
