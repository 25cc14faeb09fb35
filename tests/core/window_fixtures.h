// Frames for the window checks' tests (energy_check.h, residual_check.h): noisy means of a
// known truth whose errors have exactly the variance the planes state.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

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

// `mean` (channel-major planes) blended with itself shifted `shift` pixels along the
// flattened plane: a·x̄ + (1 − a)·x̄ shifted, an output that smears what the means hold.
inline std::vector<float> blended_with_shift(const std::vector<float>& mean, float a, int shift)
{
    const std::size_t n = std::size_t(kW) * kH;
    std::vector<float> out(mean.size());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = a * mean[i] + (1 - a) * mean[(i / n) * n + (i % n + shift) % n];
    return out;
}

// `out` with every pixel further than `reach` from (cx, cy) (in the larger of the two axis
// distances) tripled: what a check at (cx, cy) must not read.
inline std::vector<float> changed_beyond(std::vector<float> out, int cx, int cy, int reach)
{
    const std::size_t n = std::size_t(kW) * kH;
    for (int c = 0; c < kChannels; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                if (std::max(std::abs(x - cx), std::abs(y - cy)) > reach)
                    out[c * n + std::size_t(y) * kW + x] *= 3.f;
    return out;
}

// A window check gives the same bits for one thread and two, and at (cx, cy), where it
// must act on `out`, reads the output within `reach` alone: changing every pixel further
// away leaves that pixel's bits. `check` is the check's function, run with `options`.
template <class Check, class Options>
void expect_thread_count_free_and_local(Check check, const Options& options,
                                        const StatisticsPlanes& s, const std::vector<float>& out,
                                        int cx, int cy, int reach)
{
    const std::size_t n = std::size_t(kW) * kH;
    std::vector<float> one = out, two = out;
    EXPECT_GT(check(s.view(), planes_of(one), options, 1), 0u);
    check(s.view(), planes_of(two), options, 2);
    EXPECT_EQ(one, two);
    std::vector<float> far = changed_beyond(out, cx, cy, reach);
    check(s.view(), planes_of(far), options, 2);
    for (int c = 0; c < kChannels; ++c) {
        const std::size_t i = c * n + std::size_t(cy) * kW + cx;
        EXPECT_NE(one[i], out[i]) << "the check must act there, channel " << c;
        EXPECT_EQ(far[i], one[i]) << "channel " << c;
    }
}

// A window check's bad options and missing planes are errors, and radius 0 reads nothing.
// `check` is the check's function; Options{radius, alpha} its options.
template <class Options, class Check>
void expect_bad_options_and_missing_planes_are_errors(Check check)
{
    const StatisticsPlanes s = noisy_means(flat, 4);
    std::vector<float> out = s.mean;
    auto run = [&](const StatisticsView& view, const std::vector<Plane>& planes, int radius,
                   double alpha) {
        return check(view, planes, Options{radius, alpha}, 0);
    };
    EXPECT_THROW(run(s.view(), planes_of(out), -1, 0.005), std::invalid_argument);
    EXPECT_THROW(run(s.view(), planes_of(out), 3, 0.0), std::invalid_argument);
    EXPECT_THROW(run(s.view(), planes_of(out), 3, 1.0), std::invalid_argument);
    EXPECT_THROW(run(s.view(), {planes_of(out)[0]}, 3, 0.005), std::invalid_argument);
    StatisticsPlanes no_variance = s;
    no_variance.variance.clear();
    EXPECT_THROW(run(no_variance.view(), planes_of(out), 3, 0.005), std::invalid_argument);
    EXPECT_EQ(run(no_variance.view(), planes_of(out), 0, 0.005), 0u)
        << "radius 0 is off and reads nothing";
}

}  // namespace statmc::window_fixtures
