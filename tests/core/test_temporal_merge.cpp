// Temporal members (core/temporal_merge.h): merging what the test accepts from
// neighbouring frames, following motion vectors, and refusing what it tells apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

#include "estimator_fixtures.h"
#include "shifted_statistics.h"
#include "statmc/core/temporal_merge.h"

namespace statmc {
namespace {

using testing::sample_statistics;

constexpr int kW = 64, kH = 48;

// Normal samples of known σ, so that the merged mean's error is predictable.
float sigma_of(float mean) { return 0.2f * mean + 0.05f; }
float draw_known_normal(std::mt19937_64& rng, float mean)
{
    return std::normal_distribution<float>(mean, sigma_of(mean))(rng);
}

float smooth_truth(int x, int y, int c) { return 0.5f + 0.3f * std::sin(0.1f * x + 0.07f * y + c); }

std::vector<StatisticsPlanes> static_sequence(int frames, int spp, const testing::TruthFn& truth)
{
    std::vector<StatisticsPlanes> seq;
    for (int k = 0; k < frames; ++k)
        seq.push_back(sample_statistics(kW, kH, spp, truth, draw_known_normal, 1000 + k));
    return seq;
}

std::vector<TemporalFrame> frames_of(const std::vector<StatisticsPlanes>& planes)
{
    std::vector<TemporalFrame> frames;
    for (const StatisticsPlanes& p : planes)
        frames.push_back({p.view(), {}, {}});
    return frames;
}

DenoiseOptions test_options() { return DenoiseOptions{}; }

TEST(TemporalMerge, StaticSequenceLowersTheErrorByTheMergedSampleCount)
{
    const int spp = 8;
    const auto seq = static_sequence(5, spp, smooth_truth);
    const auto frames = frames_of(seq);
    const StatisticsPlanes merged =
        merge_temporal_members(frames, 2, TestDomain::BoxCox, {2, 0}, test_options(), 0);

    // Predicted MSE of each mean: σ²/N with the count the merge reports; measured against
    // the truth. With 64·48·3 values the measured MSE has a relative standard error of
    // ~1.3%; the members the test rejects (≈α of them, chosen by their noise) bias it by
    // well under that, so 8% is a wide tolerance with no false failures in practice.
    double measured = 0, predicted = 0, single = 0, single_predicted = 0, counts = 0;
    const std::size_t n = std::size_t(kW) * kH;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const std::size_t i = std::size_t(y) * kW + x, k = c * n + i;
                const double t = smooth_truth(x, y, c), s2 = double(sigma_of(t)) * sigma_of(t);
                measured += std::pow(merged.mean[k] - t, 2);
                predicted += s2 / merged.count[i];
                single += std::pow(seq[2].mean[k] - t, 2);
                single_predicted += s2 / spp;
                counts += merged.count[i];
            }
    EXPECT_NEAR(measured / predicted, 1.0, 0.08);
    EXPECT_NEAR(single / single_predicted, 1.0, 0.08);
    // Nearly every member joins: the mean count is close to 5 frames' worth.
    EXPECT_GT(counts / (3.0 * n), 0.97 * 5 * spp);
    EXPECT_LT(measured / single, 0.24);  // 1/5 predicted
}

TEST(TemporalMerge, MergedStatisticsEqualOneRenderOfAllTheSamples)
{
    // Two frames of one pixel whose test must pass: the merge is the exact merge.
    const auto seq = static_sequence(2, 16, [](int, int, int) { return 1.f; });
    const auto frames = frames_of(seq);
    const StatisticsPlanes merged =
        merge_temporal_members(frames, 0, TestDomain::BoxCox, {1, 0}, test_options(), 1);
    const StatisticsPlanes both =
        StatisticsImage<3>::merged({seq[0].view(), seq[1].view()}, 1).planes();
    int joined = 0;
    for (std::size_t i = 0; i < both.count.size(); ++i)
        if (merged.count[i] == 32) {
            ++joined;
            for (int c = 0; c < 3; ++c) {
                const std::size_t k = c * both.count.size() + i;
                EXPECT_EQ(merged.mean[k], both.mean[k]);
                EXPECT_EQ(merged.variance[k], both.variance[k]);
                EXPECT_EQ(merged.bc_moment3[k], both.bc_moment3[k]);
            }
        } else {
            EXPECT_EQ(merged.count[i], 16);
        }
    EXPECT_GT(joined, int(0.98 * both.count.size()));
}

TEST(TemporalMerge, KZeroChangesNothing)
{
    const auto seq = static_sequence(3, 4, smooth_truth);
    const StatisticsPlanes merged =
        merge_temporal_members(frames_of(seq), 1, TestDomain::BoxCox, {0, 0}, test_options(), 0);
    EXPECT_EQ(merged.count, seq[1].count);
    EXPECT_EQ(merged.mean, seq[1].mean);
    EXPECT_EQ(merged.bc_variance, seq[1].bc_variance);
}

TEST(TemporalMerge, ShiftedFramesWithTheirMotionMergeAsTheUnshiftedOnes)
{
    const auto seq = static_sequence(3, 8, smooth_truth);
    const StatisticsPlanes still =
        merge_temporal_members(frames_of(seq), 1, TestDomain::BoxCox, {1, 0}, test_options(), 0);

    // A pan of (3, −2) px per frame: frame k is frame k of `seq` moved by k·(3, −2), and
    // every pixel's motion to the previous frame is (−3, +2).
    const int sx = 3, sy = -2;
    std::vector<StatisticsPlanes> moved;
    for (int k = 0; k < 3; ++k)
        moved.push_back(test::shifted(seq[k], k * sx, k * sy, test::Entering::Empty));
    const std::vector<float> mx(std::size_t(kW) * kH, float(-sx)), my(mx.size(), float(-sy));
    std::vector<TemporalFrame> frames;
    for (const StatisticsPlanes& p : moved)
        frames.push_back({p.view(), dense_plane(mx.data(), kW), dense_plane(my.data(), kW)});
    const StatisticsPlanes pan =
        merge_temporal_members(frames, 1, TestDomain::BoxCox, {1, 0}, test_options(), 0);

    // Pixel (x, y) of the moved centre is (x − 3, y + 2) of the still one. Where the pixel
    // and its correspondences in frames 0 and 2 are all inside, the bits agree.
    const std::size_t n = std::size_t(kW) * kH;
    int compared = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const int u = x - sx, v = y - sy;
            if (u - sx < 0 || v - sy < 0 || u + sx >= kW || v + sy >= kH || u < 0 || v >= kH ||
                x + sx >= kW || y + sy < 0)
                continue;
            ++compared;
            const std::size_t i = std::size_t(y) * kW + x, j = std::size_t(v) * kW + u;
            ASSERT_EQ(pan.count[i], still.count[j]) << x << "," << y;
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(pan.mean[c * n + i], still.mean[c * n + j]) << x << "," << y;
        }
    EXPECT_GT(compared, kW * kH / 2);
}

TEST(TemporalMerge, ForwardMotionThatDoesNotLandBackIsADisocclusion)
{
    const auto seq = static_sequence(2, 4, smooth_truth);
    // Frame 1's pixels all claim to come from (10, 10) of frame 0: only (10, 10) of frame 0
    // can be followed forward, and only to where the search lands exactly back on it.
    const std::vector<float> zero(std::size_t(kW) * kH, 0.f);
    std::vector<float> mx(zero.size()), my(zero.size());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            mx[std::size_t(y) * kW + x] = float(10 - x);
            my[std::size_t(y) * kW + x] = float(10 - y);
        }
    const std::vector<TemporalFrame> frames = {
        {seq[0].view(), dense_plane(zero.data(), kW), dense_plane(zero.data(), kW)},
        {seq[1].view(), dense_plane(mx.data(), kW), dense_plane(my.data(), kW)}};
    int ox = -1, oy = -1;
    EXPECT_TRUE(corresponding_pixel(frames, 1, 0, 30, 20, ox, oy));  // backwards: defined
    EXPECT_EQ(ox, 10);
    EXPECT_EQ(oy, 10);
    EXPECT_FALSE(corresponding_pixel(frames, 0, 1, 30, 20, ox, oy));
    EXPECT_FALSE(corresponding_pixel(frames, 0, 0, 30, 20, ox, oy));  // not another frame
}

// A bright region whose edge moves 4 px per frame over a darker one (dark enough to differ
// by many standard errors, bright enough that normal samples are never negative, which
// the accumulators would count as 0).
float edge_truth(int frame, int x, int c) { return x < 20 + 4 * frame ? 4.f + 0.1f * c : 0.5f; }

TEST(TemporalMerge, WrongMotionVectorsGhostNothing)
{
    // The motion layers say "static" while the edge moves: every pixel between the edges'
    // positions is offered a member from the other side. Over 3 standard errors of the
    // merged estimate from the truth of frame t, outside 1 px of its edge, is a ghost.
    const int spp = 16, frames_n = 5, centre = 2;
    std::vector<StatisticsPlanes> seq;
    for (int k = 0; k < frames_n; ++k)
        seq.push_back(sample_statistics(
            kW, kH, spp, [k](int x, int, int c) { return edge_truth(k, x, c); }, draw_known_normal,
            77 + k));
    const std::vector<float> zero(std::size_t(kW) * kH, 0.f);
    std::vector<TemporalFrame> frames;
    for (const StatisticsPlanes& p : seq)
        frames.push_back({p.view(), dense_plane(zero.data(), kW), dense_plane(zero.data(), kW)});
    std::vector<float> members(zero.size());
    const StatisticsPlanes merged =
        merge_temporal_members(frames, centre, TestDomain::BoxCox, {2, 1}, test_options(), 0,
                               dense_plane(members.data(), kW));

    const std::size_t n = std::size_t(kW) * kH;
    const int edge = 20 + 4 * centre;
    int checked = 0, ghosts = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            if (std::abs(x + 0.5 - edge) <= 1)
                continue;  // the pixel's centre is within 1 px of the edge
            const std::size_t i = std::size_t(y) * kW + x;
            for (int c = 0; c < 3; ++c) {
                const double t = edge_truth(centre, x, c);
                const double se = sigma_of(float(t)) / std::sqrt(double(merged.count[i]));
                ++checked;
                ghosts += std::abs(merged.mean[c * n + i] - t) > 3 * se;
            }
        }
    // Legitimate merges exceed 3 SE with probability 0.27% each: ~0.3% of the checks.
    // One ghosted member frame moves a dark pixel by 16·3.5/336 ≈ 0.17, some 20 SE.
    EXPECT_LT(double(ghosts) / checked, 0.01);
    // The members that do join are the same-side ones: far from the edges nearly all
    // 4 frames × 5 disk pixels join.
    EXPECT_GT(members[std::size_t(10) * kW + 5], 15);
    EXPECT_GT(members[std::size_t(10) * kW + 60], 15);
}

TEST(TemporalMerge, TheFireflyGuardKeepsAFireflyOut)
{
    const int spp = 16;
    auto seq = static_sequence(2, spp, [](int, int, int) { return 0.5f; });
    // One sample of 500 in pixel (7, 7) of frame 1: its Box-Cox variance is far above the
    // centre's noise level.
    StatisticsImage<3> img = StatisticsImage<3>::from_view(seq[1].view());
    const float firefly[3] = {500.f, 500.f, 500.f};
    img.add(7, 7, firefly);
    seq[1] = img.planes();
    const auto frames = frames_of(seq);
    const std::size_t i = std::size_t(7) * kW + 7;

    const StatisticsPlanes guarded =
        merge_temporal_members(frames, 0, TestDomain::BoxCox, {1, 0}, test_options(), 0);
    EXPECT_EQ(guarded.count[i], spp);
    DenoiseOptions unguarded = test_options();
    unguarded.firefly_ratio = 0;
    const StatisticsPlanes paper =
        merge_temporal_members(frames, 0, TestDomain::BoxCox, {1, 0}, unguarded, 0);
    EXPECT_EQ(paper.count[i], 2 * spp + 1);  // its huge variance passes the plain test
}

TEST(TemporalMerge, AMovingLightEdgeDoesNotStraddleIntoADarkPixel)
{
    // Pixel (8, 8) is dark in frame 0 (n = 16, a little noise), between pixels that straddle
    // a light (a quarter of their samples 17, the rest dark), so its neighbourhood's noise
    // level is high and the spatial guard would take almost anything. In frame 1 the
    // light's edge has moved by a fraction of a pixel and (8, 8) straddles it too. The
    // symmetric test passes (the straddle's variance covers the difference); the temporal
    // guard, against the centre's own level, must refuse it.
    const int n = 16;
    std::mt19937_64 rng(5);
    std::normal_distribution<float> dark_noise(0.006f, 0.002f);
    auto dark = [&] {
        const float v = std::max(0.f, dark_noise(rng));
        return std::array<float, 3>{v, v, v};
    };
    StatisticsImage<3> f0(kW, kH), f1(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int i = 0; i < n; ++i) {
                const bool straddles0 =
                    (x != 8 || y != 8) && std::abs(x - 8) + std::abs(y - 8) <= 2;
                const bool straddles1 = std::abs(x - 8) + std::abs(y - 8) <= 2;
                const std::array<float, 3> light{17.f, 17.f, 17.f};
                f0.add(x, y, (straddles0 && i % 4 == 0 ? light : dark()).data());
                f1.add(x, y, (straddles1 && i % 4 == 0 ? light : dark()).data());
            }
    const StatisticsPlanes p0 = f0.planes(), p1 = f1.planes();
    const std::vector<TemporalFrame> frames = {{p0.view(), {}, {}}, {p1.view(), {}, {}}};
    const StatisticsPlanes merged =
        merge_temporal_members(frames, 0, TestDomain::BoxCox, {1, 0}, test_options(), 0);
    const std::size_t i = std::size_t(8) * kW + 8;
    EXPECT_EQ(merged.count[i], n);
    EXPECT_LT(merged.mean[i], 0.05f);
    // Far from the light, dark pixels still merge.
    EXPECT_EQ(merged.count[std::size_t(30) * kW + 40], 2 * n);
}

TEST(TemporalMerge, BitwiseTheSameForAnyThreadCount)
{
    const auto seq = static_sequence(5, 4, smooth_truth);
    const auto frames = frames_of(seq);
    const StatisticsPlanes one =
        merge_temporal_members(frames, 2, TestDomain::BoxCox, {2, 2}, test_options(), 1);
    const StatisticsPlanes all =
        merge_temporal_members(frames, 2, TestDomain::BoxCox, {2, 2}, test_options(), 0);
    EXPECT_EQ(one.count, all.count);
    EXPECT_EQ(one.mean, all.mean);
    EXPECT_EQ(one.bc_moment4, all.bc_moment4);
}

TEST(TemporalMerge, UntransformedStatisticsMergeWithoutBoxCoxPlanes)
{
    auto seq = static_sequence(3, 8, smooth_truth);
    for (StatisticsPlanes& p : seq)
        p.bc_mean.clear(), p.bc_variance.clear(), p.bc_moment3.clear(), p.bc_moment4.clear();
    const StatisticsPlanes merged = merge_temporal_members(
        frames_of(seq), 1, TestDomain::Untransformed, {1, 0}, test_options(), 0);
    EXPECT_TRUE(merged.bc_mean.empty());
    double mean_count = 0;
    for (float n : merged.count)
        mean_count += n;
    EXPECT_GT(mean_count / merged.count.size(), 0.97 * 24);
}

TEST(TemporalMerge, MismatchedFramesAreRefused)
{
    const auto seq = static_sequence(2, 4, smooth_truth);
    auto small = sample_statistics(kW / 2, kH, 4, smooth_truth, draw_known_normal, 5);
    EXPECT_THROW(merge_temporal_members({{seq[0].view(), {}, {}}, {small.view(), {}, {}}}, 0,
                                        TestDomain::BoxCox, {1, 0}, test_options(), 0),
                 std::invalid_argument);
    const std::vector<float> zero(std::size_t(kW) * kH, 0.f);
    EXPECT_THROW(merge_temporal_members(
                     {{seq[0].view(), dense_plane(zero.data(), kW), dense_plane(zero.data(), kW)},
                      {seq[1].view(), {}, {}}},
                     0, TestDomain::BoxCox, {1, 0}, test_options(), 0),
                 std::invalid_argument);
    StatisticsPlanes fewer = seq[1];
    fewer.moment3.clear(), fewer.moment4.clear();  // a frame without M3/M4
    EXPECT_THROW(merge_temporal_members({{seq[0].view(), {}, {}}, {fewer.view(), {}, {}}}, 0,
                                        TestDomain::BoxCox, {1, 0}, test_options(), 0),
                 std::invalid_argument);
    EXPECT_THROW(
        merge_temporal_members(frames_of(seq), 2, TestDomain::BoxCox, {1, 0}, test_options(), 0),
        std::invalid_argument);
    EXPECT_THROW(
        merge_temporal_members(frames_of(seq), 0, TestDomain::BoxCox, {-1, 0}, test_options(), 0),
        std::invalid_argument);
}

}  // namespace
}  // namespace statmc
