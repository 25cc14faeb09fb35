// The per-sample values of the per-bounce quantities, computed by hand from a path record,
// their statistics, steering's compact statistics and their batched denoising.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "same_bits.h"
#include "statmc/core/estimator_image.h"
#include "statmc/render/bounce_statistics.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/steering_statistics.h"

using namespace statmc::render;

namespace {

float luminance(float r, float g, float b) { return Rgb{r, g, b}.luminance(); }

PathRecord example_record()
{
    using T = PathRecord::Technique;
    PathRecord r;
    r.throughput = {Rgb{1.f}, Rgb{0.5f}, Rgb{0.25f, 0.f, 0.25f}};
    r.roulette_weight = {1.f, 1.f, 2.f};  // roulette survived with p = 1/2 after vertex 1
    r.contributions = {
        {0, T::Emission, 1.f, Rgb{1.f}},               // arrives at 0
        {0, T::Light, 0.8f, Rgb{0.2f}},                // at 0, light wins
        {0, T::Bsdf, 0.3f, Rgb{0.1f}},                 // found at 1, light wins (w ≤ 0.5)
        {1, T::Light, 0.4f, Rgb{0.05f}},               // at 1, BSDF wins
        {1, T::Bsdf, 0.9f, Rgb{0.025f, 0.f, 0.025f}},  // found at 2, BSDF wins
    };
    return r;
}

}  // namespace

TEST(BounceStatistics, SampleValuesFollowTheDefinitions)
{
    const BounceLayout layout{3, 2};
    ASSERT_EQ(layout.quantities(), 7);
    float v[7];
    bounce_sample(example_record(), layout, v);
    EXPECT_FLOAT_EQ(v[layout.luminance(0)], luminance(1.375f, 1.35f, 1.375f));
    // Vertex 1: (0.1 + 0.05 + 0.025) / 0.5 per channel (green lacks the last 0.025).
    EXPECT_FLOAT_EQ(v[layout.luminance(1)], luminance(0.35f, 0.3f, 0.35f));
    // Vertex 2: 0.025 / 0.25 in red and blue, green has no throughput; roulette weight 2.
    EXPECT_FLOAT_EQ(v[layout.luminance(2)], 2 * luminance(0.1f, 0.f, 0.1f));
    EXPECT_EQ(v[layout.light_wins(0)], 2.f);
    EXPECT_EQ(v[layout.bsdf_wins(0)], 0.f);
    EXPECT_EQ(v[layout.light_wins(1)], 0.f);
    EXPECT_EQ(v[layout.bsdf_wins(1)], 2.f);
}

TEST(BounceStatistics, DeeperVerticesGatherIntoTheLastTrackedOne)
{
    const BounceLayout layout{2, 1};
    float v[4];
    bounce_sample(example_record(), layout, v);
    // L_1 takes every contribution arriving at vertex ≥ 1.
    EXPECT_FLOAT_EQ(v[layout.luminance(1)], luminance(0.35f, 0.3f, 0.35f));
    EXPECT_EQ(v[layout.light_wins(0)], 2.f);
    EXPECT_EQ(v[layout.bsdf_wins(0)], 0.f);  // vertex 1's wins are not tracked
}

TEST(BounceStatistics, UnreachedVerticesAreZero)
{
    PathRecord r;
    r.throughput = {Rgb{1.f}};
    r.roulette_weight = {1.f};
    r.contributions = {{0, PathRecord::Technique::Emission, 1.f, Rgb{2.f}}};
    const BounceLayout layout{4, 2};
    float v[8];
    bounce_sample(r, layout, v);
    EXPECT_FLOAT_EQ(v[0], 2.f);
    for (int i = 1; i < 8; ++i)
        EXPECT_EQ(v[i], 0.f) << i;
}

TEST(BounceStatistics, BatchedDenoisingMatchesTheStatistics)
{
    // Six quantities in two filter groups (4 + 2). A constant quantity (zero variance)
    // must come out exactly, and a noisy one within its spread; L̂ of a pixel that is
    // every neighbour's twin is their mean.
    constexpr int kW = 12, kH = 10;
    SteeringStatistics steering(kW, kH, BounceLayout{4, 1});
    BounceStatistics stats(kW, kH, BounceLayout{4, 1});
    std::uint32_t state = 1;
    auto uniform = [&] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) * 0x1p-24f;
    };
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int s = 0; s < 16; ++s) {
                const float v[6] = {1.5f, uniform(), 0.25f, 0.f, float(s % 2), 2.f};
                steering.add(x, y, v);
                stats.add(x, y, v);
            }
    const BounceEstimates est = steering.denoise(statmc::DenoiseOptions{});
    ASSERT_EQ(est.values.size(), std::size_t(kW * kH * 6));
    for (std::size_t i = 0; i < std::size_t(kW * kH); ++i) {
        const PixelEstimates p = est.pixel(i);
        EXPECT_FLOAT_EQ(p.luminance(0), 1.5f);
        EXPECT_FLOAT_EQ(p.luminance(2), 0.25f);
        EXPECT_EQ(p.luminance(3), 0.f);
        EXPECT_EQ(p.luminance(7), 0.f);           // beyond the tracked ones: the last
        EXPECT_NEAR(p.luminance(1), 0.5f, 0.1f);  // mean of ≥ 16 uniforms: sd ≤ 0.072
        EXPECT_NEAR(p.light_wins(0), 0.5f, 1e-6f);
        EXPECT_FLOAT_EQ(p.bsdf_wins(0), 2.f);
    }
    // The stored statistics of one quantity, as the EXR layer gets them.
    const auto groups = stats.group_planes();
    ASSERT_EQ(groups.size(), 2u);
    const statmc::StatisticsView q5 = BounceStatistics::quantity_view(groups, 5);
    EXPECT_EQ(q5.channels, 1);
    EXPECT_EQ(q5.mean[0](3, 4), 2.f);
    EXPECT_EQ(q5.count(3, 4), 16.f);
    EXPECT_EQ(q5.variance[0](3, 4), 0.f);
}

// Steering keeps only the moments its estimates read; they are core's updates stopped at
// the third moment, so its estimates are, to the bit, those of core's filter on the full
// statistics (four quantities to a filter call, Box-Cox test), here with heavy-tailed
// samples, zeros and 11 quantities in three groups.
TEST(SteeringStatistics, EstimatesAreThoseOfTheFullStatisticsToTheBit)
{
    constexpr int kW = 23, kH = 17;
    const BounceLayout layout{5, 3};  // 5 luminances, 2 win counts at 3 vertices
    const int q_total = layout.quantities();
    SteeringStatistics steering(kW, kH, layout);
    BounceStatistics full(kW, kH, layout);
    std::uint32_t state = 7;
    auto uniform = [&] {
        state = state * 1664525u + 1013904223u;
        return (float(state >> 8) + 0.5f) * 0x1p-24f;
    };
    std::vector<float> v(std::size_t(q_total), 0.f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int s = 0; s < 3 + (x + y) % 9; ++s) {
                for (int q = 0; q < q_total; ++q) {
                    const float u = uniform();
                    // Mostly dark, sometimes a heavy-tailed hit (1/u²), win counts 0 or 1.
                    v[std::size_t(q)] =
                        q < 5 ? (u < 0.7f ? 0.f : 0.1f / (u * u) * float(x % 4)) : float(u < 0.5f);
                }
                steering.add(x, y, v.data());
                full.add(x, y, v.data());
            }
    const statmc::DenoiseOptions options = estimates_filter();
    const BounceEstimates got = steering.denoise(options, 1);
    // Core's filter on the full statistics, one group at a time.
    const std::vector<statmc::StatisticsPlanes> groups = full.group_planes();
    std::vector<float> want(std::size_t(kW * kH * q_total));
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const int first = int(g) * BounceStatistics::kGroup;
        statmc::StatisticsView view = groups[g].view();
        view.channels = std::min(BounceStatistics::kGroup, q_total - first);
        std::vector<statmc::Plane> out;
        for (int c = 0; c < view.channels; ++c)
            out.push_back({want.data() + first + c, q_total, std::ptrdiff_t(kW) * q_total});
        statmc::filter(statmc::estimators_from_statistics(view, statmc::TestDomain::BoxCox), {},
                       options, out, {}, 1);
    }
    ASSERT_EQ(got.values.size(), want.size());
    int differing = 0;
    for (std::size_t i = 0; i < want.size(); ++i)
        differing += !statmc::test::same_bits(got.values[i], want[i]);
    EXPECT_EQ(differing, 0) << "of " << want.size();
}

// A sample that is not a number (a path whose throughput underflowed) counts as 0, as
// core's accumulators count an unusable sample.
TEST(SteeringStatistics, AnUnusableValueCountsAsZero)
{
    SteeringStatistics steering(1, 1, BounceLayout{1, 0});
    for (float v : {2.f, std::numeric_limits<float>::infinity(),
                    std::numeric_limits<float>::quiet_NaN(), -1.f, 4.f})
        steering.add(0, 0, &v);
    EXPECT_EQ(steering.counts()[0], 5.0);
    EXPECT_DOUBLE_EQ(steering.moments()[0].mean, 6.0 / 5.0);
}
