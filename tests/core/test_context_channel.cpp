// The context channel (context_channel.h): its box means and variances against a direct
// computation, and what it is for: a pixel row on a light's edge, whose samples mostly miss
// the light, keeps its own expectation instead of the dark surface's beside it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/context_channel.h"
#include "statmc/core/filter.h"
#include "statmc/core/firefly_guard.h"
#include "statmc/core/statistics_image.h"
#include "filter_fixtures.h"

namespace statmc {
namespace {

EstimatorImage ramp(int w, int h, int channels)
{
    EstimatorImage e(w, h, channels);
    e.domain = TestDomain::BoxCox;
    for (int c = 0; c < channels; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t k = e.index(c, x, y);
                e.count[std::size_t(y) * w + x] = 8 + x;
                e.value[k] = float(c + 10 * x + 100 * y);
                e.test_mean[k] = float(c + x + 2 * y);
                e.test_variance[k] = float(1 + c + x * y);
            }
    return e;
}

TEST(ContextChannel, IsTheMeanOfTheChosenChannelAroundThePixelOverTestablePixels)
{
    constexpr int w = 7, h = 5;
    EstimatorImage est = ramp(w, h, 3);
    est.count[std::size_t(2) * w + 3] = 1;  // (3, 2) untestable: in no box
    const EstimatorImage ctx = with_context(est, 1, 1, 0);
    ASSERT_EQ(ctx.channels, 4);
    EXPECT_EQ(ctx.domain, TestDomain::BoxCox);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < 3; ++c) {  // the pixel's own channels are unchanged
                EXPECT_EQ(ctx.test_mean[ctx.index(c, x, y)], est.test_mean[est.index(c, x, y)]);
                EXPECT_EQ(ctx.value[ctx.index(c, x, y)], est.value[est.index(c, x, y)]);
            }
            double mean = 0, variance = 0, value = 0;
            int k = 0;
            for (int yy = y - 1; yy <= y + 1; ++yy)
                for (int xx = x - 1; xx <= x + 1; ++xx)
                    if (xx >= 0 && yy >= 0 && xx < w && yy < h && !(xx == 3 && yy == 2) &&
                        !(xx == x && yy == y)) {
                        mean += est.test_mean[est.index(1, xx, yy)];
                        variance += est.test_variance[est.index(1, xx, yy)];
                        value += est.value[est.index(1, xx, yy)];
                        ++k;
                    }
            ASSERT_GT(k, 0);
            EXPECT_FLOAT_EQ(ctx.test_mean[ctx.index(3, x, y)], float(mean / k)) << x << "," << y;
            EXPECT_FLOAT_EQ(ctx.test_variance[ctx.index(3, x, y)], float(variance / (k * k)));
            EXPECT_FLOAT_EQ(ctx.value[ctx.index(3, x, y)], float(value / k));
        }
    // A corner's box holds three pixels besides itself: a mean of three has a ninth of
    // their summed variance.
    EXPECT_FLOAT_EQ(ctx.test_variance[ctx.index(3, 0, 0)], float((2 + 2 + 3) / 9.0));
    EXPECT_EQ(ctx.test_variance, with_context(est, 1, 1, 0, 1).test_variance);  // any thread count
    EXPECT_THROW(with_context(est, 3, 1, 0), std::invalid_argument);
    EXPECT_THROW(with_context(est, 1, 0, 0), std::invalid_argument);
    EXPECT_THROW(with_context(ramp(w, h, kMaxEstimatorChannels), 0, 1, 0), std::invalid_argument);
}

TEST(ContextChannel, LeavesTheFireflyGuardAsItWas)
{
    // The guard reads the pixels' own channels only: a context that holds a firefly must
    // not raise its neighbours' levels (they would then accept the firefly), and a black
    // pixel in a lit context must stay black to the guard (it takes any level).
    constexpr int w = 9, h = 7;
    EstimatorImage est = ramp(w, h, 3);
    for (int c = 0; c < 3; ++c) {
        est.test_variance[est.index(c, 4, 3)] = 1e6f;  // a firefly
        est.value[est.index(c, 1, 1)] = 0;             // a black pixel
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x)
                est.test_variance[est.index(c, x, y)] = 0;  // in a noise-free corner
    }
    const NoiseLevels plain = noise_levels(est, 256);
    const NoiseLevels with = noise_levels(with_context(est, 1, 1, 256), 256);
    EXPECT_EQ(with.level, plain.level);
    EXPECT_EQ(with.limit, plain.limit);
    EXPECT_EQ(plain.limit[std::size_t(1) * w + 1], std::numeric_limits<float>::infinity());
}

// Two rows of a light (17, constant), one row that sees a sliver of it (a sample hits it
// with p = 0.02, else the ceiling's value), and the ceiling (normal, mean 0.15, sd 0.05),
// 64 samples per pixel. The edge row's expectation is 0.98 · 0.15 + 0.02 · 17 = 0.487, but
// 28% of its pixels have no hit and look like the ceiling.
StatisticsPlanes light_edge(std::uint64_t seed)
{
    constexpr int w = 120, h = 9, spp = 64;
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> ceiling(0.15f, 0.05f);
    std::bernoulli_distribution hit(0.02);
    StatisticsImage<3> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < spp; ++s) {
                const float v = y < 2                ? 17.f
                                : y == 2 && hit(rng) ? 17.f
                                                     : std::max(ceiling(rng), 0.f);
                const float rgb[3] = {v, v, v};
                img.add(x, y, rgb);
            }
    return img.planes();
}

double edge_row_mean(const EstimatorImage& est)
{
    std::vector<float> out(est.pixels() * est.channels);
    std::vector<Plane> planes;
    for (int c = 0; c < est.channels; ++c)
        planes.push_back(dense_plane(out.data() + c * est.pixels(), est.width));
    filter(est, {}, DenoiseOptions{}, planes, {}, 2);
    double sum = 0;
    for (int x = 20; x < est.width - 20; ++x)
        sum += out[est.index(1, x, 2)];
    return sum / (est.width - 40);
}

TEST(ContextChannel, KeepsALightsEdgeRowFromTheSurfaceBesideIt)
{
    const StatisticsPlanes stats = light_edge(7);
    const EstimatorImage est = estimators_from_statistics(stats.view(), TestDomain::BoxCox);
    const double truth = 0.98 * 0.15 + 0.02 * 17;
    const double plain = edge_row_mean(est);
    const double with = edge_row_mean(with_context(est, 1, 1, DenoiseOptions{}.firefly_ratio));
    // The row holds 80 × 64 × 0.02 ≈ 102 hits: its own mean is within about 10% (one sd)
    // of the truth, and an average over its members no further off than that allows.
    EXPECT_NEAR(with, truth, 0.3 * truth) << "plain " << plain;
    // Without the context the ceiling's members pull the row far down (seeds 1-3 and 7: 0.197
    // to 0.204 without, 0.458 to 0.503 with).
    EXPECT_LT(plain, 0.6 * truth) << "with " << with;
}

// The kernels test a context channel but do not average it (filter_layout.h, averaged):
// the other channels come out with the bits they have when the context channel is
// averaged too, at every SIMD level, with and without guides, and its plane is left alone.
TEST(ContextChannel, IsTestedButNotAveragedWithTheSameBitsElsewhere)
{
    constexpr int w = 53, h = 31;
    DenoiseOptions options;
    options.radius = 4;
    options.firefly_ratio = 0;  // the guard's levels leave context channels out; not here
    for (int channels : {1, 2, 3}) {  // 2: no kernel of its own, the general one
        const EstimatorImage tested =
            with_context(random_estimators(w, h, channels, 40 + channels), channels - 1, 1, 0);
        ASSERT_EQ(tested.context_channels, 1);
        EstimatorImage averaged = tested;
        averaged.context_channels = 0;
        for (bool guided : {false, true}) {
            const GuideImages g(w, h, guided, guided, 9);
            for (SimdLevel level : supported_simd_levels()) {
                SCOPED_TRACE(std::string(simd_level_name(level)) + ", channels " +
                             std::to_string(channels) + (guided ? ", guides" : ""));
                Output a(w, h, channels + 1), b(w, h, channels + 1);
                const float kUntouched = -7.f;
                std::fill(a.values.begin() + std::size_t(channels) * w * h, a.values.end(),
                          kUntouched);
                filter(tested, g.guides, options, a.planes(), a.diagnostics(), 2, level);
                filter(averaged, g.guides, options, b.planes(), b.diagnostics(), 2, level);
                const std::size_t own = std::size_t(channels) * w * h;
                EXPECT_TRUE(std::equal(a.values.begin(), a.values.begin() + own,
                                       b.values.begin()));
                EXPECT_EQ(a.members, b.members);
                EXPECT_EQ(a.effective, b.effective);
                EXPECT_TRUE(std::all_of(a.values.begin() + own, a.values.end(),
                                        [&](float v) { return v == kUntouched; }));
                // The averaged context plane is a real average, unlike the left-alone one.
                EXPECT_FALSE(std::equal(a.values.begin() + own, a.values.end(),
                                        b.values.begin() + own));
            }
        }
    }
}

}  // namespace
}  // namespace statmc
