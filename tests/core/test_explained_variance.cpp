// The position co-moments (two-pass reference, exact merge) and the explained-variance
// correction on pixels whose analytic residual variance is known.
#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/explained_variance.h"
#include "statmc/core/statistics_image.h"

namespace statmc {
namespace {

struct Sample {
    double f, u, v;
};

// Σ(f − f̄)(u − ū) and the other sums, two-pass.
struct TwoPass {
    double cu = 0, cv = 0, uu = 0, vv = 0, uv = 0;
};

TwoPass two_pass(const std::vector<Sample>& s)
{
    double f = 0, u = 0, v = 0;
    for (const Sample& x : s)
        f += x.f, u += x.u, v += x.v;
    f /= double(s.size()), u /= double(s.size()), v /= double(s.size());
    TwoPass t;
    for (const Sample& x : s) {
        t.cu += (x.f - f) * (x.u - u);
        t.cv += (x.f - f) * (x.v - v);
        t.uu += (x.u - u) * (x.u - u);
        t.vv += (x.v - v) * (x.v - v);
        t.uv += (x.u - u) * (x.v - v);
    }
    return t;
}

std::vector<Sample> draw(int n, std::mt19937_64& rng)
{
    std::uniform_real_distribution<double> uniform(0, 1);
    std::exponential_distribution<double> expo(1.0);
    std::vector<Sample> s(n);
    for (Sample& x : s) {
        x.u = uniform(rng);
        x.v = uniform(rng);
        x.f = 3 * x.u + expo(rng);
    }
    return s;
}

TEST(PositionMoments, OnlineMatchesTwoPassAndMergeOfSplitsEqualsWhole)
{
    std::mt19937_64 rng(11);
    const std::vector<Sample> s = draw(300, rng);
    auto accumulate = [&](std::size_t begin, std::size_t end, PixelMoments<1>& px,
                          PositionMoments<1>& q) {
        for (std::size_t i = begin; i < end; ++i) {
            const float f = float(s[i].f);
            px.add(&f, float(s[i].u), float(s[i].v), q);
        }
    };
    PixelMoments<1> whole;
    PositionMoments<1> qw;
    accumulate(0, s.size(), whole, qw);
    // The reference from the float values that were added.
    std::vector<Sample> as_added = s;
    for (Sample& x : as_added)
        x = {double(float(x.f)), double(float(x.u)), double(float(x.v))};
    const TwoPass t = two_pass(as_added);
    EXPECT_NEAR(qw.raw_u[0], t.cu, 1e-10 * s.size());
    EXPECT_NEAR(qw.raw_v[0], t.cv, 1e-10 * s.size());
    EXPECT_NEAR(qw.m2_uu, t.uu, 1e-12 * s.size());
    EXPECT_NEAR(qw.m2_vv, t.vv, 1e-12 * s.size());
    EXPECT_NEAR(qw.m2_uv, t.uv, 1e-12 * s.size());
    for (std::size_t split : {std::size_t(1), std::size_t(37), std::size_t(150)}) {
        PixelMoments<1> a, b;
        PositionMoments<1> qa, qb;
        accumulate(0, split, a, qa);
        accumulate(split, s.size(), b, qb);
        a.merge(b, qa, qb);
        EXPECT_NEAR(qa.raw_u[0], qw.raw_u[0], 1e-10 * s.size()) << split;
        EXPECT_NEAR(qa.bc_v[0], qw.bc_v[0], 1e-10 * s.size()) << split;
        EXPECT_NEAR(qa.m2_uv, qw.m2_uv, 1e-12 * s.size()) << split;
        EXPECT_NEAR(qa.mean_u, qw.mean_u, 1e-14) << split;
        EXPECT_EQ(a.n, whole.n);
    }
}

// An image whose every pixel draws `spp` samples f(u, v) + N(0, σ) at uniform positions.
StatisticsPlanes render(int size, int spp, double sigma, std::uint64_t seed,
                        const std::function<double(double, double)>& f)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::normal_distribution<double> noise(0, sigma);
    StatisticsImage<1> img(size, size, true);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            for (int i = 0; i < spp; ++i) {
                const double u = uniform(rng), v = uniform(rng);
                const float value = float(f(u, v) + noise(rng));
                img.add(x, y, &value, u, v);
            }
    return img.planes();
}

double mean_of(const std::vector<float>& v)
{
    double sum = 0;
    for (float x : v)
        sum += x;
    return sum / double(v.size());
}

// 32² pixels of 64 samples: the mean over pixels of s²_r has a standard error of
// σ²·sqrt(2/61)/32 ≈ 0.6% of σ², so ±3% is five of them.
constexpr int kSize = 32, kSpp = 64;
constexpr double kSigma = 0.1;

TEST(ExplainedVariance, AGradientAcrossThePixelIsRemovedDownToTheNoise)
{
    // Far from negative, so that the Box-Cox transform (√) stays near-linear.
    const StatisticsPlanes p =
        render(kSize, kSpp, kSigma, 1, [](double u, double v) { return 5 + 2 * u - v; });
    const ExplainedVariance e = remove_explained_variance(p.view());
    // Uncorrected: σ² + (2² + 1²)/12 = 0.427.
    EXPECT_NEAR(mean_of(p.variance), kSigma * kSigma + 5.0 / 12, 0.03 * (5.0 / 12));
    EXPECT_NEAR(mean_of(e.variance), kSigma * kSigma, 0.03 * kSigma * kSigma);
    EXPECT_EQ(e.corrected_pixels, std::size_t(2 * kSize * kSize));  // both domains, all
}

TEST(ExplainedVariance, AHalfCoveredPixelKeepsOnlyWhatNoPlaneExplains)
{
    // A step of height h at u = ½ (an edge through the pixel centre): its variance h²/4
    // is 3/4 linear in u (Cov(step, u)²/Var(u) = (h/8)²·12 = 3h²/16), leaving h²/16. Above
    // 0, since core counts a negative sample as 0.
    const double h = 1;
    const StatisticsPlanes p =
        render(kSize, kSpp, kSigma, 2, [&](double u, double) { return u < 0.5 ? 1 + h : 1.0; });
    const ExplainedVariance e = remove_explained_variance(p.view());
    const double noise = kSigma * kSigma;
    EXPECT_NEAR(mean_of(p.variance), noise + h * h / 4, 0.03 * (noise + h * h / 4));
    EXPECT_NEAR(mean_of(e.variance), noise + h * h / 16, 0.03 * (noise + h * h / 16));
}

TEST(ExplainedVariance, NoiseOnlyPixelsAreCorrectedAtTheTestsRateAndOtherwiseKept)
{
    // Under the null (no gradient, normal noise) the F test fires at rate α: 4096 pixels
    // at α = 0.05 give 204.8 ± 13.9; five standard deviations either side fail the test
    // by chance with probability < 1e-6.
    const int size = 64, spp = 16;
    const StatisticsPlanes p = render(size, spp, 1.0, 3, [](double, double) { return 10.0; });
    StatisticsView raw_only = p.view();
    raw_only.bc_mean = raw_only.bc_variance = raw_only.bc_moment3 = {};
    const ExplainedVariance e = remove_explained_variance(raw_only, {0.05});
    EXPECT_GT(e.corrected_pixels, 135u);
    EXPECT_LT(e.corrected_pixels, 275u);
    EXPECT_TRUE(e.bc_variance.empty());
    std::size_t kept = 0;
    for (std::size_t i = 0; i < p.variance.size(); ++i)
        kept += e.variance[i] == p.variance[i];
    EXPECT_EQ(kept, p.variance.size() - e.corrected_pixels);
}

TEST(ExplainedVariance, HigherMomentsKeepTheirShapeAndThreadsDoNotMatter)
{
    const StatisticsPlanes p =
        render(16, 32, 0.2, 4, [](double u, double v) { return 4 + 3 * u * v; });
    const ExplainedVariance one = remove_explained_variance(p.view(), {}, 1);
    const ExplainedVariance two = remove_explained_variance(p.view(), {}, 2);
    EXPECT_EQ(one.variance, two.variance);
    EXPECT_EQ(one.bc_moment4, two.bc_moment4);
    for (std::size_t i = 0; i < p.variance.size(); ++i) {
        const double r = double(one.variance[i]) / p.variance[i];
        EXPECT_NEAR(one.moment4[i], p.moment4[i] * r * r, 1e-5 * p.moment4[i]);
        EXPECT_NEAR(one.moment3[i], p.moment3[i] * r * std::sqrt(r),
                    1e-5 * std::abs(p.moment3[i]) + 1e-12);
    }
}

TEST(ExplainedVariance, TooFewSamplesOrNoPositionsAreLeftAloneOrRefused)
{
    const StatisticsPlanes p = render(4, 3, 0.1, 5, [](double u, double) { return 1 + 5 * u; });
    const ExplainedVariance e = remove_explained_variance(p.view());
    EXPECT_EQ(e.corrected_pixels, 0u);
    EXPECT_EQ(e.variance, p.variance);
    StatisticsPlanes without = p;
    without.cov_u.clear();
    EXPECT_THROW(remove_explained_variance(without.view()), std::invalid_argument);
    // All samples at one position: no plane to fit.
    EXPECT_LT(residual_second_moment(1, 0, 0, 0, 0, 0), 0);
}

TEST(StatisticsImage, PositionPlanesRoundTripAndMergeExactly)
{
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::gamma_distribution<float> gamma(0.7f, 2.f);
    StatisticsImage<3> a(5, 4, true), b(5, 4, true), all(5, 4, true);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x)
            for (int i = 0; i < 40; ++i) {
                const float s[3] = {gamma(rng), gamma(rng), gamma(rng)};
                const double u = uniform(rng), v = uniform(rng);
                (i < 13 + x ? a : b).add(x, y, s, u, v);
                all.add(x, y, s, u, v);
            }
    const StatisticsPlanes pa = a.planes(), pb = b.planes(), pall = all.planes();
    const StatisticsPlanes merged = StatisticsImage<3>::merged({pa.view(), pb.view()}, 1).planes();
    auto expect_close = [](const std::vector<float>& got, const std::vector<float>& want,
                           const char* what) {
        ASSERT_EQ(got.size(), want.size()) << what;
        for (std::size_t i = 0; i < want.size(); ++i)
            EXPECT_NEAR(got[i], want[i], 1e-5f * std::abs(want[i]) + 1e-6f) << what << " " << i;
    };
    expect_close(merged.subpixel_u, pall.subpixel_u, "subpixel_u");
    expect_close(merged.subpixel_uv, pall.subpixel_uv, "subpixel_uv");
    expect_close(merged.cov_u, pall.cov_u, "cov_u");
    expect_close(merged.bc_cov_v, pall.bc_cov_v, "bc_cov_v");
    // Untracked on one side: the merge drops positions rather than invent them.
    StatisticsImage<3> untracked(5, 4);
    a.merge(untracked);
    EXPECT_FALSE(a.tracks_positions());
    EXPECT_TRUE(a.planes().cov_u.empty());
}

}  // namespace
}  // namespace statmc
