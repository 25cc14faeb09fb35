// The benchmarks' frame: the reference size, 1280×720 RGB at n = 64, with
// render-like statistics and guides. Shared by the filter and operator benchmarks.
#pragma once

#include <random>
#include <vector>

#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/statistics_image.h"

namespace statmc::bench {

constexpr int kWidth = 1280, kHeight = 720, kSamples = 64;

// A render-like frame: smooth shading, a few hard edges, exponential noise. With
// fireflies, one pixel in 500 has one sample 1000× brighter, so the firefly guard has
// work to do in most chunks. `seed` draws another frame of the same (static) shot.
inline StatisticsPlanes make_frame(bool fireflies, std::uint64_t seed = 1)
{
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> one_in_500(0, 499);
    StatisticsImage<3> img(kWidth, kHeight);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const float shade = 0.2f + 0.6f * float(x) / kWidth + ((x / 160 + y / 120) % 2) * 0.5f;
            std::exponential_distribution<float> expo(1.f / shade);
            const bool firefly = fireflies && one_in_500(rng) == 0;
            for (int i = 0; i < kSamples; ++i) {
                const float gain = firefly && i == 0 ? 1000.f : 1.f;
                const float s[3] = {gain * expo(rng), gain * 0.8f * expo(rng),
                                    gain * 0.6f * expo(rng)};
                img.add(x, y, s);
            }
        }
    return img.planes();
}

inline const StatisticsPlanes& frame(bool fireflies = false)
{
    static const StatisticsPlanes clean = make_frame(false);
    if (!fireflies)
        return clean;
    static const StatisticsPlanes with_fireflies = make_frame(true);
    return with_fireflies;
}

/// Albedo and normal planes with the frame's edges, at the frame's size or another; with
/// `noise`, also their variances (docs/method.md §5, guide noise), larger on the edges.
struct GuidePlanes {
    std::vector<float> data, variance;
    Guides guides;
    explicit GuidePlanes(int width = kWidth, int height = kHeight, bool noise = false)
        : data(std::size_t(6) * width * height), variance(std::size_t(width) * height)
    {
        const std::size_t n = std::size_t(width) * height;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int k = 0; k < 6; ++k)
                    data[k * n + std::size_t(y) * width + x] =
                        0.1f * k + ((x / 160 + y / 120) % 2) * 0.3f;
        for (int k = 0; k < 3; ++k) {
            guides.albedo[k] = dense_plane(data.data() + k * n, width);
            guides.normal[k] = dense_plane(data.data() + (k + 3) * n, width);
        }
        if (!noise)
            return;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                variance[std::size_t(y) * width + x] = x % 160 == 0 || y % 120 == 0 ? 0.3f : 0.01f;
        guides.albedo_variance = dense_plane(variance.data(), width);
        guides.normal_variance = dense_plane(variance.data(), width);
    }
};

/// `tile`'s estimators repeated (or cut) to width × height.
inline EstimatorImage tiled(const EstimatorImage& tile, int width, int height)
{
    EstimatorImage out(width, height, tile.channels);
    out.domain = tile.domain;
    for (int c = 0; c < tile.channels; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t from = tile.index(c, x % tile.width, y % tile.height);
                const std::size_t to = out.index(c, x, y);
                out.value[to] = tile.value[from];
                out.test_mean[to] = tile.test_mean[from];
                out.test_variance[to] = tile.test_variance[from];
                if (c == 0)
                    out.count[to] = tile.count[from];
            }
    return out;
}

}  // namespace statmc::bench
