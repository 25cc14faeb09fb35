// Online moments and their merge against a two-pass brute-force computation.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/box_cox.h"
#include "statmc/core/moments.h"
#include "statmc/core/pixel_moments.h"
#include "statmc/core/statistics_image.h"

namespace statmc {
namespace {

struct BruteForce {
    double n = 0, mean = 0, m2 = 0, m3 = 0, m4 = 0;
};

BruteForce two_pass(const std::vector<double>& xs)
{
    BruteForce b;
    b.n = double(xs.size());
    for (double x : xs)
        b.mean += x;
    b.mean /= b.n;
    for (double x : xs) {
        b.m2 += (x - b.mean) * (x - b.mean);
        b.m3 += (x - b.mean) * (x - b.mean) * (x - b.mean);
        b.m4 += (x - b.mean) * (x - b.mean) * (x - b.mean) * (x - b.mean);
    }
    return b;
}

CentralMoments<double> online(const std::vector<double>& xs, std::size_t begin, std::size_t end)
{
    CentralMoments<double> m;
    for (std::size_t i = begin; i < end; ++i)
        m.add(double(i - begin), xs[i]);
    return m;
}

// Relative agreement scaled by the magnitude the sums can reach, so that a sum that
// cancels to ~0 is compared against its terms, not against 0.
void expect_moments_near(const CentralMoments<double>& m, const BruteForce& b, double scale)
{
    EXPECT_NEAR(m.mean, b.mean, 1e-12 * scale);
    EXPECT_NEAR(m.m2, b.m2, 1e-10 * b.n * scale * scale);
    EXPECT_NEAR(m.m3, b.m3, 1e-9 * b.n * scale * scale * scale);
    EXPECT_NEAR(m.m4, b.m4, 1e-9 * b.n * scale * scale * scale * scale);
}

std::vector<double> draw(const char* kind, int n, std::mt19937_64& rng)
{
    std::vector<double> xs(n);
    std::normal_distribution<double> normal(3.0, 2.0);
    std::exponential_distribution<double> expo(0.5);
    std::lognormal_distribution<double> logn(0.0, 1.5);
    for (double& x : xs) {
        if (std::string(kind) == "normal")
            x = normal(rng);
        else if (std::string(kind) == "exponential")
            x = expo(rng);
        else
            x = logn(rng);
    }
    return xs;
}

TEST(Moments, OnlineMatchesTwoPass)
{
    std::mt19937_64 rng(1);
    for (const char* kind : {"normal", "exponential", "lognormal"})
        for (int n : {1, 2, 3, 17, 1000}) {
            const auto xs = draw(kind, n, rng);
            double scale = 0;
            for (double x : xs)
                scale = std::max(scale, std::abs(x));
            SCOPED_TRACE(std::string(kind) + " n=" + std::to_string(n));
            expect_moments_near(online(xs, 0, xs.size()), two_pass(xs), scale);
        }
}

TEST(Moments, MergeOfRandomSplitsEqualsWhole)
{
    std::mt19937_64 rng(2);
    for (int trial = 0; trial < 200; ++trial) {
        const auto xs = draw(trial % 2 ? "lognormal" : "normal", 2 + int(rng() % 300), rng);
        // Cut into up to 6 random pieces (empty pieces included) and merge left to right.
        std::vector<std::size_t> cuts = {0, xs.size()};
        for (int k = 0; k < 5; ++k)
            cuts.push_back(rng() % (xs.size() + 1));
        std::sort(cuts.begin(), cuts.end());
        CentralMoments<double> total;
        double n = 0;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
            total.merge(n, online(xs, cuts[k], cuts[k + 1]), double(cuts[k + 1] - cuts[k]));
            n += double(cuts[k + 1] - cuts[k]);
        }
        double scale = 0;
        for (double x : xs)
            scale = std::max(scale, std::abs(x));
        ASSERT_EQ(n, double(xs.size()));
        expect_moments_near(total, two_pass(xs), scale);
    }
}

TEST(Moments, StableForLargeOffsetInFloat)
{
    // Values 1e4 + small noise: naive Σx² − n·mean² in float would lose every digit.
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.f, 0.01f);
    std::vector<double> xs;
    CentralMoments<float> m;
    for (int i = 0; i < 10000; ++i) {
        const float x = 1e4f + noise(rng);
        m.add(float(i), x);
        xs.push_back(x);
    }
    const BruteForce b = two_pass(xs);
    EXPECT_NEAR(m.m2 / (b.n - 1), b.m2 / (b.n - 1), 0.02 * b.m2 / (b.n - 1));
}

TEST(PixelMoments, TracksRawAndBoxCoxAndCountsBrokenSamplesAsZero)
{
    std::mt19937_64 rng(4);
    std::exponential_distribution<float> expo(1.f);
    PixelMoments<3> px;
    std::vector<double> raw[3], bc[3];
    for (int i = 0; i < 500; ++i) {
        float s[3] = {expo(rng), expo(rng), expo(rng)};
        if (i % 50 == 7)
            s[1] = std::nanf("");
        if (i % 50 == 9)
            s[0] = INFINITY;
        if (i % 50 == 11)
            s[2] = -1.f;  // luminance −0.07: broken sample
        const bool usable = std::isfinite(s[0]) && std::isfinite(s[1]) && std::isfinite(s[2]) &&
                            luminance(double(s[0]), double(s[1]), double(s[2])) >= -1e-5;
        for (int c = 0; c < 3; ++c) {
            const double x = usable ? s[c] : 0.0;
            raw[c].push_back(x);
            bc[c].push_back(2 * std::sqrt(std::max(x, 0.0)) - 2);  // negative channels clamp
        }
        px.add(s);
    }
    EXPECT_EQ(px.n, 500);
    for (int c = 0; c < 3; ++c) {
        expect_moments_near(px.raw[c], two_pass(raw[c]), 10);
        expect_moments_near(px.box_cox[c], two_pass(bc[c]), 10);
    }
}

TEST(BoxCox, IsTwoSqrtMinusTwoAndClampsNegatives)
{
    EXPECT_DOUBLE_EQ(box_cox(4.0), 2.0);
    EXPECT_DOUBLE_EQ(box_cox(1.0), 0.0);
    EXPECT_DOUBLE_EQ(box_cox(0.0), -2.0);
    EXPECT_DOUBLE_EQ(box_cox(-3.0), -2.0);
    // λ = ½: (x^λ − 1)/λ
    EXPECT_NEAR(box_cox(2.5), (std::pow(2.5, 0.5) - 1) / 0.5, 1e-15);
}

TEST(StatisticsImage, PlanesRoundTripAndMergeEqualsAccumulatingAll)
{
    std::mt19937_64 rng(5);
    std::gamma_distribution<float> gamma(0.7f, 2.f);
    StatisticsImage<3> a(5, 4), b(5, 4), all(5, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
            for (int i = 0; i < 40; ++i) {
                const float s[3] = {gamma(rng), gamma(rng), gamma(rng)};
                (i < 13 + x ? a : b).add(x, y, s);
                all.add(x, y, s);
            }
    a.merge(b);
    const StatisticsPlanes pa = a.planes(), pall = all.planes();
    for (std::size_t i = 0; i < pall.count.size(); ++i)
        EXPECT_EQ(pa.count[i], pall.count[i]);
    for (std::size_t i = 0; i < pall.mean.size(); ++i) {
        EXPECT_NEAR(pa.mean[i], pall.mean[i], 1e-6f * std::abs(pall.mean[i]) + 1e-7f);
        EXPECT_NEAR(pa.variance[i], pall.variance[i], 1e-5f * pall.variance[i] + 1e-7f);
        EXPECT_NEAR(pa.bc_mean[i], pall.bc_mean[i], 1e-5f * std::abs(pall.bc_mean[i]) + 1e-7f);
        EXPECT_NEAR(pa.bc_variance[i], pall.bc_variance[i], 1e-5f * pall.bc_variance[i] + 1e-7f);
        EXPECT_NEAR(pa.bc_moment3[i], pall.bc_moment3[i],
                    1e-4f * std::abs(pall.bc_moment3[i]) + 1e-6f);
    }
    // Planes → accumulators → planes is the identity (up to float rounding).
    const StatisticsPlanes back = StatisticsImage<3>::from_view(pall.view()).planes();
    for (std::size_t i = 0; i < pall.mean.size(); ++i) {
        EXPECT_FLOAT_EQ(back.variance[i], pall.variance[i]);
        EXPECT_FLOAT_EQ(back.bc_moment3[i], pall.bc_moment3[i]);
    }
}

TEST(StatisticsImage, OneSampleHasZeroStoredVarianceAndCountOne)
{
    StatisticsImage<1> img(1, 1);
    const float s = 3.f;
    img.add(0, 0, &s);
    const StatisticsPlanes p = img.planes();
    EXPECT_EQ(p.count[0], 1.f);
    EXPECT_EQ(p.mean[0], 3.f);
    EXPECT_EQ(p.variance[0], 0.f);
    EXPECT_EQ(p.bc_moment3[0], 0.f);
}

}  // namespace
}  // namespace statmc
