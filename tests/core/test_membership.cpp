// The membership test: the Welch/optimal-weight identities of the seed (Eqs. S.1–S.8)
// and the filter's decisions against an independent Welch t-test.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"

namespace statmc {
namespace {

TEST(WeightIdentities, OptimalWeightIsAFunctionOfWelchT)
{
    std::mt19937_64 rng(11);
    std::lognormal_distribution<double> scale(0.0, 2.0);
    for (int i = 0; i < 10000; ++i) {
        const double delta = scale(rng) * (rng() % 2 ? 1 : -1);
        const double v = scale(rng);
        const double w = (2 * delta * delta + v) / (2 * (delta * delta + v));  // Eq. 12
        const double s = 1 - w;
        const double t = std::abs(delta) / std::sqrt(v);  // Eq. S.1
        ASSERT_GE(w, 0.5);
        ASSERT_LE(w, 1.0);
        EXPECT_NEAR(s, 1 - (t * t + 0.5) / (t * t + 1), 1e-12);  // Eq. S.5
        if (s > 1e-6) {
            EXPECT_NEAR(t, std::sqrt(1 / (2 * s) - 1), 1e-6 * (1 + t));  // Eq. S.6
        }
    }
}

TEST(WeightIdentities, ThresholdOnWeightEqualsWelchTest)
{
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> tdist(0.0, 8.0);
    for (double gamma_w : {1.96, 2.807, 4.317, 12.7}) {
        const double gamma = 1 / (2 * (gamma_w * gamma_w + 1));  // Eq. S.7
        for (int i = 0; i < 5000; ++i) {
            const double t = tdist(rng);
            if (std::abs(t - gamma_w) < 1e-9)
                continue;
            const double s = 1 - (t * t + 0.5) / (t * t + 1);
            EXPECT_EQ(s > gamma, t < gamma_w) << "t " << t << " gamma_w " << gamma_w;
        }
    }
}

TEST(WeightIdentities, ExpandedFastFormEqualsSquaredWelch)
{
    // Eq. S.8: with D = μ² − γ²v, D_i + D_j ≤ 2μ_iμ_j ⇔ (μ_i − μ_j)² ≤ γ²(v_i + v_j).
    std::mt19937_64 rng(13);
    std::normal_distribution<double> mu(0.0, 3.0);
    std::exponential_distribution<double> var(1.0);
    const double g = 2.807;
    int disagreements = 0, n = 0;
    for (int i = 0; i < 100000; ++i) {
        const double mi = mu(rng), mj = mu(rng), vi = var(rng), vj = var(rng);
        const double lhs = (mi - mj) * (mi - mj), rhs = g * g * (vi + vj);
        if (std::abs(lhs - rhs) < 1e-9 * (1 + rhs))
            continue;  // too close to call in double
        const double di = mi * mi - g * g * vi, dj = mj * mj - g * g * vj;
        disagreements += (di + dj <= 2 * mi * mj) != (lhs <= rhs);
        ++n;
    }
    EXPECT_EQ(disagreements, 0) << "of " << n;
}

// A 2×1 image whose two pixels hold the given estimators; the filter's member count at
// pixel 0 (with radius 1) says whether pixel 1 passed the test.
bool filter_says_member(float mi, float vi, float mj, float vj, float n, double alpha,
                        SimdLevel level)
{
    EstimatorImage est(2, 1, 1);
    est.count = {n, n};
    est.value = {mi, mj};
    est.test_mean = {mi, mj};
    est.test_variance = {vi, vj};
    DenoiseOptions opt;
    opt.radius = 1;
    opt.alpha = alpha;
    float out[2], members[2];
    filter(est, {}, opt, {dense_plane(out, 2)}, {dense_plane(members, 2), {}, {}}, 1, level);
    EXPECT_EQ(members[0], members[1]) << "the test is symmetric";
    return members[0] == 2.f;
}

TEST(Membership, EqualCountsGiveExactlyWelchsTest)
{
    std::mt19937_64 rng(14);
    std::normal_distribution<double> mu(1.0, 0.5);
    std::lognormal_distribution<double> var(-4.0, 1.0);
    for (SimdLevel level : supported_simd_levels())
        for (double alpha : {0.005, 0.05}) {
            int checked = 0, members = 0;
            for (int n : {2, 4, 16, 64, 4096}) {
                for (int i = 0; i < 400; ++i) {
                    const float mi = float(mu(rng)), mj = float(mu(rng));
                    const float vi = float(var(rng)), vj = float(var(rng));
                    // Welch (Eq. S.1) with df = n_i + n_j − 2, computed independently.
                    const double t = std::abs(double(mi) - mj) / std::sqrt(double(vi) + vj);
                    const double gw = CriticalValues::exact(alpha, 2.0 * n - 2);
                    if (std::abs(t - gw) < 1e-4 * gw)
                        continue;  // float rounding could go either way
                    const bool welch = t < gw;
                    EXPECT_EQ(filter_says_member(mi, vi, mj, vj, float(n), alpha, level), welch)
                        << simd_level_name(level) << " n " << n << " t " << t << " gamma " << gw;
                    ++checked;
                    members += welch;
                }
            }
            EXPECT_GT(checked, 1500);
            EXPECT_GT(members, 100);  // both outcomes well exercised
            EXPECT_LT(members, checked - 100);
        }
}

TEST(Membership, UntestablePixelsAreNobodysMember)
{
    for (SimdLevel level : supported_simd_levels()) {
        // n = 1: undefined variance.
        EXPECT_FALSE(filter_says_member(1.f, 0.1f, 1.f, 0.1f, 1.f, 0.005, level));
        // Non-finite test inputs.
        EXPECT_FALSE(filter_says_member(1.f, NAN, 1.f, 0.1f, 8.f, 0.005, level));
        EXPECT_FALSE(filter_says_member(1.f, INFINITY, 1.f, 0.1f, 8.f, 0.005, level));
        EXPECT_FALSE(filter_says_member(1.f, -0.1f, 1.f, 0.1f, 8.f, 0.005, level));
        // Zero variance is defined: equal means pass, any difference fails.
        EXPECT_TRUE(filter_says_member(1.f, 0.f, 1.f, 0.f, 8.f, 0.005, level));
        EXPECT_FALSE(filter_says_member(1.f, 0.f, 1.0001f, 0.f, 8.f, 0.005, level));
    }
}

TEST(Membership, DifferenceFormKeepsPrecisionWhereExpandedFormCancels)
{
    // μ ≈ 100 with v = 1e-7: γ²v ≈ 8e-7 is below float's resolution of μ² (≈ 1e-3),
    // so D = μ² − γ²v rounds to μ² and the expanded test degenerates. The difference
    // form still separates means 2e-3 apart (t ≈ 4.5 > γ) and joins 2e-4 apart (t ≈ 0.45).
    const float v = 1e-7f;
    for (SimdLevel level : supported_simd_levels()) {
        EXPECT_FALSE(filter_says_member(100.f, v, 100.002f, v, 1e6f, 0.005, level));
        EXPECT_TRUE(filter_says_member(100.f, v, 100.0002f, v, 1e6f, 0.005, level));
    }
}

}  // namespace
}  // namespace statmc
