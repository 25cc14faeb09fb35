// Synthetic per-pixel estimators for filter tests: samples with a known truth per pixel,
// accumulated with core's own accumulators.
#pragma once

#include <functional>
#include <random>
#include <vector>

#include "statmc/core/estimator_image.h"
#include "statmc/core/statistics_image.h"

namespace statmc::testing {

/// truth(x, y, c) gives the expected value; draw(rng, mean) one sample with that mean.
using TruthFn = std::function<float(int x, int y, int c)>;
using DrawFn = std::function<float(std::mt19937_64& rng, float mean)>;

inline StatisticsPlanes sample_statistics(int w, int h, int n, const TruthFn& truth,
                                          const DrawFn& draw, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    StatisticsImage<3> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int i = 0; i < n; ++i) {
                float s[3];
                for (int c = 0; c < 3; ++c)
                    s[c] = draw(rng, truth(x, y, c));
                img.add(x, y, s);
            }
    return img.planes();
}

inline float draw_exponential(std::mt19937_64& rng, float mean)
{
    return mean <= 0 ? 0.f : std::exponential_distribution<float>(1.f / mean)(rng);
}

inline float draw_normal(std::mt19937_64& rng, float mean)
{
    return std::normal_distribution<float>(mean, 0.3f * mean + 0.01f)(rng);
}

// Heavy-tailed: log-normal with σ_log = 1.2, scaled to the requested mean.
inline float draw_lognormal(std::mt19937_64& rng, float mean)
{
    const float s = 1.2f;
    return mean * std::lognormal_distribution<float>(-0.5f * s * s, s)(rng);
}

/// Mean squared error of dense planes (channel-major) against the truth.
inline double mse(const std::vector<float>& planes, int w, int h, int channels,
                  const TruthFn& truth)
{
    double sum = 0;
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double d =
                    planes[std::size_t(c) * w * h + std::size_t(y) * w + x] - truth(x, y, c);
                sum += d * d;
            }
    return sum / (double(w) * h * channels);
}

}  // namespace statmc::testing
