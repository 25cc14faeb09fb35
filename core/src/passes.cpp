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
    out.moment3.assign(n * channels, 0.f);
    out.moment4.assign(n * channels, 0.f);

    // The K samples of one pixel, read and sanitised once, then summed in two passes
    // (mean, then powers of the deviations) so the moments have no cancellation.
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
                double m2 = 0, m3 = 0, m4 = 0;
                for (int r = 0; r < k; ++r) {
                    const double d = samples[std::size_t(r) * channels + c] - mean;
                    m2 += d * d;
                    m3 += d * d * d;
                    m4 += d * d * d * d;
                }
                out.mean[c * n + i] = float(mean);
                out.variance[c * n + i] = float(m2 / (k - 1));
                out.moment3[c * n + i] = float(m3 / k);
                out.moment4[c * n + i] = float(m4 / k);
            }
        }
    return out;
}

}  // namespace statmc
