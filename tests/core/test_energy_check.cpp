// The energy check (docs/method.md §16): where a window's output holds another amount of
// light than its noisy means, beyond their noise, the output is scaled back; elsewhere it
// keeps its bits.
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/energy_check.h"
#include "statmc/core/statistics_image.h"
#include "window_fixtures.h"

namespace statmc {
namespace {

using namespace window_fixtures;

constexpr EnergyCheckOptions kCheck{3, 0.005};

bool in_patch(int x, int y, int margin)
{
    return x >= 20 + margin && x < 44 - margin && y >= 12 + margin && y < 36 - margin;
}

TEST(EnergyCheck, AnOutputThatKeepsEveryWindowsLightKeepsItsBits)
{
    const StatisticsPlanes s = noisy_means(flat, 1);
    std::vector<float> out = s.mean;  // the noisy means themselves: every sum agrees
    EXPECT_EQ(keep_window_energy(s.view(), planes_of(out), kCheck), 0u);
    EXPECT_EQ(out, s.mean);
}

TEST(EnergyCheck, GivesBackLightAFilterLostAndTakesBackLightItInvented)
{
    // An output that halved a 24×24 patch (lost light) or doubled it (invented light). Deep
    // inside it every window is off by far more than its noise (Σ 0.5·x̄ ≈ 98 against
    // z·sqrt(49/16) ≈ 4.9), each factor is 2 (or 1/2) and so is their average: the noisy
    // means come back, to rounding. Outside the patch's reach nothing changes.
    const StatisticsPlanes s = noisy_means(flat, 2);
    const std::size_t n = std::size_t(kW) * kH;
    for (const float scale : {0.5f, 2.f}) {
        std::vector<float> out = s.mean;
        for (int c = 0; c < kChannels; ++c)
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    if (in_patch(x, y, 0))
                        out[c * n + std::size_t(y) * kW + x] *= scale;
        EXPECT_GT(keep_window_energy(s.view(), planes_of(out), kCheck), 0u);
        for (int c = 0; c < kChannels; ++c)
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const std::size_t i = c * n + std::size_t(y) * kW + x;
                    if (in_patch(x, y, 2 * kCheck.radius)) {
                        ASSERT_NEAR(out[i], s.mean[i], 1e-5f * s.mean[i])
                            << "scale " << scale << " at " << x << "," << y;
                    }
                    if (!in_patch(x, y, -2 * kCheck.radius)) {
                        ASSERT_EQ(out[i], s.mean[i])
                            << "scale " << scale << " at " << x << "," << y;
                    }
                }
    }
}

TEST(EnergyCheck, APixelThatMovedTheOtherWayKeepsItsBits)
{
    // The patch lost half its light, but one pixel in it took light (1.5·x̄): the windows
    // around it give factors near 2, which would scale that pixel further from its mean.
    // It keeps its bits; its neighbours, which lost light, are scaled back up.
    const StatisticsPlanes s = noisy_means(flat, 5);
    const std::size_t n = std::size_t(kW) * kH;
    std::vector<float> out = s.mean;
    for (int c = 0; c < kChannels; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                if (in_patch(x, y, 0))
                    out[c * n + std::size_t(y) * kW + x] *= 0.5f;
    const std::size_t took = 24 * kW + 32, beside = took + 1;
    for (int c = 0; c < kChannels; ++c)
        out[c * n + took] = 1.5f * s.mean[c * n + took];
    const std::vector<float> before = out;
    keep_window_energy(s.view(), planes_of(out), kCheck);
    for (int c = 0; c < kChannels; ++c) {
        EXPECT_EQ(out[c * n + took], before[c * n + took]) << "channel " << c;
        EXPECT_GT(out[c * n + beside], 1.5f * before[c * n + beside]) << "channel " << c;
    }
}

TEST(EnergyCheck, FindsAnUnbiasedOutputOffAtItsLevel)
{
    // The output is the truth itself, so each window's difference Σ x̄ − Σ μ is normal with
    // exactly the variance the test uses: a window is found off with probability α, and
    // over five seeds of 3 × 64 × 48 windows about α·N ≈ 230 are. Windows overlap, so
    // their verdicts come in clusters of a few dozen at most: the count stays within
    // [α·N/3, 2·α·N] but for a chance well below one in a thousand.
    const double windows = 5.0 * kChannels * kW * kH;
    double off = 0;
    for (std::uint64_t seed = 10; seed < 15; ++seed) {
        const StatisticsPlanes s = noisy_means(flat, seed);
        std::vector<float> out(s.mean.size());
        for (int c = 0; c < kChannels; ++c)
            std::fill(out.begin() + std::size_t(c) * kW * kH,
                      out.begin() + std::size_t(c + 1) * kW * kH, flat(0, 0, c));
        off += double(keep_window_energy(s.view(), planes_of(out), kCheck));
    }
    EXPECT_LE(off, 2 * kCheck.alpha * windows);
    EXPECT_GE(off, kCheck.alpha * windows / 3);
}

TEST(EnergyCheck, IsTheSameForAnyThreadCountAndReadsTheOutputWithinTwiceItsRadius)
{
    // At (29, 20), the column that took light from across the edge.
    const StatisticsPlanes s =
        noisy_means([](int x, int, int c) { return x < 30 ? 1.f + c : 8.f; }, 3);
    expect_thread_count_free_and_local(keep_window_energy, kCheck, s,
                                       blended_with_shift(s.mean, 0.7f, 1), 29, 20,
                                       2 * kCheck.radius);
}

TEST(EnergyCheck, BadOptionsAndMissingPlanesAreErrors)
{
    expect_bad_options_and_missing_planes_are_errors<EnergyCheckOptions>(keep_window_energy);
}

}  // namespace
}  // namespace statmc
