// Synthetic per-pixel estimators for filter tests: samples with a known truth per pixel,
// accumulated with core's own accumulators.
#pragma once

#include <cmath>
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

/// A 4-channel estimator image written by hand, 37 × 11: random means and variances, and
/// every way a pixel can be untestable (n < 2, a NaN or infinite mean or variance, a
/// negative variance), beside zero means and ±0 variances; the last `context` channels
/// are context channels.
inline EstimatorImage odd_estimators(TestDomain domain, int context, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    EstimatorImage est(37, 11, 4);
    est.domain = domain;
    est.context_channels = context;
    for (std::size_t i = 0; i < est.pixels(); ++i)
        est.count[i] = u(rng) < 0.05f ? 1.f : 2.f + std::floor(100 * u(rng));
    const float odd[] = {NAN, INFINITY, -INFINITY, -1e-3f, 0.f, -0.f};
    for (std::size_t i = 0; i < est.test_mean.size(); ++i) {
        est.test_mean[i] = u(rng) < 0.1f ? 0.f : 4 * u(rng) - 1;
        est.test_variance[i] = 1e-3f * u(rng);
        if (u(rng) < 0.05f)
            (u(rng) < 0.5f ? est.test_mean[i] : est.test_variance[i]) = odd[int(6 * u(rng)) % 6];
    }
    return est;
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
