#include "statmc/core/passes.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "statmc/core/box_cox.h"

namespace statmc {

StatisticsPlanes statistics_from_passes(const std::vector<std::vector<ConstPlane>>& passes,
                                        int width, int height)
{
    const int k = int(passes.size());
    if (k < 2)
        throw std::invalid_argument("need at least 2 passes, got " + std::to_string(k));
    const int channels = int(passes[0].size());
    if (channels < 1 || channels > 4)
        throw std::invalid_argument("passes must have 1 to 4 channels");
    for (const auto& pass : passes)
        if (int(pass.size()) != channels)
            throw std::invalid_argument("passes differ in their channel count");
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("empty resolution");

    StatisticsPlanes out;
    out.width = width;
    out.height = height;
    out.channels = channels;
    const std::size_t n = std::size_t(width) * height;
    out.count.assign(n, float(k));
    out.mean.assign(n * channels, 0.f);
    out.variance.assign(n * channels, 0.f);

    // The K samples of one pixel, read and sanitised once, then summed in two passes
    // (mean, then squared deviations) so the variance has no cancellation.
    std::vector<float> samples(std::size_t(k) * channels);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            for (int r = 0; r < k; ++r) {
                float* sample = &samples[std::size_t(r) * channels];
                for (int c = 0; c < channels; ++c)
                    sample[c] = passes[r][c](x, y);
                if (!sample_is_usable(sample, channels))
                    std::fill(sample, sample + channels, 0.f);
            }
            const std::size_t i = std::size_t(y) * width + x;
            for (int c = 0; c < channels; ++c) {
                double sum = 0;
                for (int r = 0; r < k; ++r)
                    sum += samples[std::size_t(r) * channels + c];
                const double mean = sum / k;
                double sum_sq = 0;
                for (int r = 0; r < k; ++r) {
                    const double d = samples[std::size_t(r) * channels + c] - mean;
                    sum_sq += d * d;
                }
                out.mean[c * n + i] = float(mean);
                out.variance[c * n + i] = float(sum_sq / (k - 1));
            }
        }
    return out;
}

}  // namespace statmc
