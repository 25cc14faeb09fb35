#include "statmc/core/passes.h"

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

    std::vector<float> sample(channels);
    auto read = [&](const std::vector<ConstPlane>& pass, int x, int y) {
        for (int c = 0; c < channels; ++c)
            sample[c] = pass[c](x, y);
        if (!sample_is_usable(sample.data(), channels))
            std::fill(sample.begin(), sample.end(), 0.f);
    };
    double sum[4], sum_sq[4];
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::fill(sum, sum + 4, 0.0);
            for (const auto& pass : passes) {
                read(pass, x, y);
                for (int c = 0; c < channels; ++c)
                    sum[c] += sample[c];
            }
            // A second pass over the K values avoids cancellation in the variance.
            std::fill(sum_sq, sum_sq + 4, 0.0);
            for (const auto& pass : passes) {
                read(pass, x, y);
                for (int c = 0; c < channels; ++c)
                    sum_sq[c] += (sample[c] - sum[c] / k) * (sample[c] - sum[c] / k);
            }
            const std::size_t i = std::size_t(y) * width + x;
            for (int c = 0; c < channels; ++c) {
                out.mean[c * n + i] = float(sum[c] / k);
                out.variance[c * n + i] = float(sum_sq[c] / (k - 1));
            }
        }
    return out;
}

}  // namespace statmc
