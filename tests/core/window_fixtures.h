// Frames for the window checks' tests (energy_check.h, residual_check.h): noisy means of a
// known truth whose errors have exactly the variance the planes state.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_image.h"

namespace statmc::window_fixtures {

constexpr int kW = 64, kH = 48, kChannels = 3;
constexpr float kCount = 16, kSigma2 = 1;  // per-sample variance; the mean's is kSigma2/kCount

// Noisy means of a known truth: truth(x, y, c) plus a normal error of the mean's exact
// variance, which the planes state, so that a check's test holds its stated rate.
template <class Truth>
StatisticsPlanes noisy_means(const Truth& truth, std::uint64_t seed, int w = kW, int h = kH)
{
    StatisticsPlanes s;
    s.width = w;
    s.height = h;
    s.channels = kChannels;
    const std::size_t n = std::size_t(w) * h;
    s.count.assign(n, kCount);
    s.mean.resize(n * kChannels);
    s.variance.assign(n * kChannels, kSigma2);
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> error(0.f, std::sqrt(kSigma2 / kCount));
    for (int c = 0; c < kChannels; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                s.mean[c * n + std::size_t(y) * w + x] = truth(x, y, c) + error(rng);
    return s;
}

inline float flat(int, int, int c) { return 4.f + c; }

// Channel-major output planes over `data`.
inline std::vector<Plane> planes_of(std::vector<float>& data, int w = kW, int h = kH)
{
    std::vector<Plane> p;
    for (int c = 0; c < kChannels; ++c)
        p.push_back(dense_plane(data.data() + std::size_t(c) * w * h, w));
    return p;
}

}  // namespace statmc::window_fixtures
