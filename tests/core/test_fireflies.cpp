// Fireflies: one extreme sample in a pixel. The paper's symmetric test lets the pixel,
// whose variance is huge, join nearly every neighbour's average; where neighbours are
// confident (detail at high spp, few members each) its value is copied into the whole
// disk and the denoised error rises above the noisy input's. The firefly guard
// (firefly_guard.h, firefly_spread.h) bounds what a firefly hands out by its own value.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "estimator_fixtures.h"
#include "statmc/core/filter.h"
#include "statmc/core/firefly_guard.h"

namespace statmc {
namespace {

using testing::TruthFn;

constexpr int kSize = 64, kFx = 32, kFy = 32;

// Every pixel a different value in [0.2, 1]: at high spp the test keeps nearly all
// neighbours apart, so each centre's average has few members.
const TruthFn kTexture = [](int x, int y, int c) {
    unsigned h = unsigned(x) * 73856093u ^ unsigned(y) * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return (0.2f + 0.8f * float(h % 1000) / 1000.f) * (1.f + 0.1f * c);
};
const TruthFn kFlat = [](int, int, int c) { return 0.5f + 0.1f * c; };

// n normal samples per pixel (σ = 5% of the mean: a well-converged render); with `firefly`, pixel (kFx, kFy)'s first sample is
// `firefly` times its truth instead.
StatisticsPlanes render(const TruthFn& truth, int n, float firefly, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    StatisticsImage<3> img(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int i = 0; i < n; ++i) {
                float s[3];
                for (int c = 0; c < 3; ++c)
                    s[c] = std::normal_distribution<float>(truth(x, y, c), 0.05f * truth(x, y, c))(rng);
                if (firefly > 0 && x == kFx && y == kFy && i == 0)
                    for (int c = 0; c < 3; ++c)
                        s[c] = firefly * truth(x, y, c);
                img.add(x, y, s);
            }
    return img.planes();
}

std::vector<float> denoise(const StatisticsPlanes& stats, float firefly_ratio, int radius = 20)
{
    const EstimatorImage est = estimators_from_statistics(stats.view(), TestDomain::BoxCox);
    std::vector<float> out(est.value.size());
    std::vector<Plane> planes;
    for (int c = 0; c < 3; ++c)
        planes.push_back(dense_plane(out.data() + c * est.pixels(), est.width));
    DenoiseOptions opt;
    opt.radius = radius;
    opt.firefly_ratio = firefly_ratio;
    filter(est, {}, opt, planes);
    return out;
}

/// Σ over pixels other than the firefly's and channels of (with − without).
double energy_added_around(const std::vector<float>& with, const std::vector<float>& without)
{
    double sum = 0;
    for (std::size_t i = 0; i < with.size(); ++i)
        if (i % (kSize * kSize) != std::size_t(kFy) * kSize + kFx)
            sum += double(with[i]) - without[i];
    return sum;
}

/// The largest rise of any channel at a pixel at least `distance` from the firefly.
double largest_rise_beyond(const std::vector<float>& with, const std::vector<float>& without, double distance)
{
    double rise = 0;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                if (std::hypot(x - kFx, y - kFy) >= distance) {
                    const std::size_t i = std::size_t(c) * kSize * kSize + std::size_t(y) * kSize + x;
                    rise = std::max(rise, double(with[i]) - without[i]);
                }
    return rise;
}

/// The firefly pixel's excess over the truth, summed over channels.
double firefly_excess(const StatisticsPlanes& fire, const TruthFn& truth)
{
    double excess = 0;
    for (int c = 0; c < 3; ++c)
        excess += fire.mean[std::size_t(c) * kSize * kSize + kFy * kSize + kFx] - truth(kFx, kFy, c);
    return excess;
}

// One sample at 20000× the truth in a well-converged textured frame (n = 256): the pixel
// is ≈ 80× too bright, an excess of ≈ 119 summed over channels.
struct ConfidentFrame : ::testing::Test {
    const StatisticsPlanes clean = render(kTexture, 256, 0, 3);
    const StatisticsPlanes fire = render(kTexture, 256, 2e4f, 3);
    const double excess = firefly_excess(fire, kTexture);
    const double noisy_mse = testing::mse(fire.mean, kSize, kSize, 3, kTexture);
};

TEST_F(ConfidentFrame, ThePapersFilterCopiesTheFireflyIntoItsDisk)
{
    // Measured: the disk holds 77× the firefly's excess; pixels 10 px away rise by 8.2;
    // the denoised MSE is 7.5× the noisy input's.
    const std::vector<float> with = denoise(fire, 0), without = denoise(clean, 0);
    EXPECT_GT(energy_added_around(with, without), 20 * excess);
    EXPECT_GT(largest_rise_beyond(with, without, 10), 1.0);
    EXPECT_GT(testing::mse(with, kSize, kSize, 3, kTexture), 2 * noisy_mse);
}

TEST_F(ConfidentFrame, TheGuardHandsOutNoMoreThanTheFireflysExcess)
{
    // Measured: 1.11× the excess around the firefly, no pixel beyond it raised by more than
    // 0.34 (0.8% of the per-channel excess), denoised MSE 1/560 of the noisy input's.
    const std::vector<float> with = denoise(fire, 16), without = denoise(clean, 16);
    EXPECT_LT(energy_added_around(with, without), 1.25 * excess);
    EXPECT_LT(largest_rise_beyond(with, without, 1), 0.02 * excess / 3);
    EXPECT_LT(testing::mse(with, kSize, kSize, 3, kTexture), noisy_mse / 100);
    // Everything the firefly does not hand out stays at the firefly: no other pixel drops.
    for (std::size_t i = 0; i < with.size(); ++i) {
        if (i % (kSize * kSize) != std::size_t(kFy) * kSize + kFx) {
            ASSERT_GE(with[i], without[i] - 1e-6f) << i;
        }
    }
}

TEST(Fireflies, WhereAveragingIsWideTheGuardIsThePapersFilter)
{
    // A flat region: every neighbour averages hundreds of members, so the paper's filter
    // already hands out ≈ the firefly's value (c_f ≈ 1) and the guard changes little.
    const StatisticsPlanes clean = render(kFlat, 64, 0, 9), fire = render(kFlat, 64, 2e4f, 9);
    const std::vector<float> paper = denoise(fire, 0), guard = denoise(fire, 16);
    const std::vector<float> paper_clean = denoise(clean, 0), guard_clean = denoise(clean, 16);
    const double paper_energy = energy_added_around(paper, paper_clean);
    const double guard_energy = energy_added_around(guard, guard_clean);
    EXPECT_NEAR(guard_energy, paper_energy, 0.1 * paper_energy);
    EXPECT_NEAR(paper_energy, firefly_excess(fire, kFlat), 0.2 * paper_energy);
}

TEST(Fireflies, TheGuardFindsTheFireflyAndRarelyAnythingElse)
{
    // The injected pixel is flagged; on clean renders flags are rare: measured 0 at
    // n ≥ 64, 0.3% at n = 16 (log-normal) and n = 4 (exponential), and 4.9% for heavy-tailed
    // log-normal noise at n = 4. A false flag costs only time: where the flagged pixel's
    // neighbours average widely the second step hands out what the paper's filter would.
    const StatisticsPlanes fire = render(kTexture, 64, 2e4f, 5);
    const std::vector<std::uint8_t> flags =
        find_fireflies(estimators_from_statistics(fire.view(), TestDomain::BoxCox), 16);
    EXPECT_EQ(flags[std::size_t(kFy) * kSize + kFx], 1);
    for (const testing::DrawFn& draw : {testing::DrawFn(testing::draw_exponential),
                                        testing::DrawFn(testing::draw_lognormal)})
        for (int n : {4, 16, 64, 256}) {
            const StatisticsPlanes stats = testing::sample_statistics(kSize, kSize, n, kTexture, draw, 11);
            const std::vector<std::uint8_t> f =
                find_fireflies(estimators_from_statistics(stats.view(), TestDomain::BoxCox), 16);
            const double rate = double(std::count(f.begin(), f.end(), 1)) / f.size();
            EXPECT_LT(rate, n >= 16 ? 0.005 : 0.06) << "n = " << n;
        }
}

TEST(Fireflies, ZeroTurnsTheGuardOff)
{
    const StatisticsPlanes fire = render(kTexture, 16, 2e4f, 5);
    const std::vector<std::uint8_t> flags =
        find_fireflies(estimators_from_statistics(fire.view(), TestDomain::BoxCox), 0);
    EXPECT_EQ(std::count(flags.begin(), flags.end(), 1), 0);
}

}  // namespace
}  // namespace statmc
