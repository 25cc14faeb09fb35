// EstimatorImage's own rules: which pixels the test may use.
#include <cfloat>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "estimator_fixtures.h"
#include "same_bits.h"

namespace statmc {
namespace {

using test::same_bits;

TEST(EstimatorImage, TestableRowIsTestableOfEachPixel)
{
    // Both forms against the rule as written in EstimatorImage's comment. Every way a pixel can be
    // untestable (n < 2, a NaN or infinite mean or variance, a negative variance), beside -0 and 0
    // variances, which are testable.
    const EstimatorImage est = testing::odd_estimators(TestDomain::BoxCox, 0, 23);
    int untestable = 0;
    std::vector<std::uint8_t> row(est.width);
    for (int y = 0; y < est.height; ++y) {
        est.testable_row(y, row.data());
        for (int x = 0; x < est.width; ++x) {
            bool expected = est.count[est.index(0, x, y)] >= 2;
            for (int c = 0; c < est.channels; ++c) {
                const float m = est.test_mean[est.index(c, x, y)];
                const float v = est.test_variance[est.index(c, x, y)];
                expected = expected && std::isfinite(m) && std::isfinite(v) && v >= 0;
            }
            ASSERT_EQ(row[x], expected ? 1 : 0) << "(" << x << ", " << y << ")";
            ASSERT_EQ(est.testable(x, y), expected) << "(" << x << ", " << y << ")";
            untestable += !row[x];
        }
    }
    EXPECT_GT(untestable, est.width);  // the fixture holds plenty of each kind
    EXPECT_LT(untestable, int(est.pixels()) / 2);
}

// estimators_from_statistics against the estimators written out pixel by pixel as
// docs/method.md §3 defines them: the same floats bit for bit, in both test domains and
// with a variance of the mean. The statistics hold every case the definitions branch on:
// n of 0, 1 and 2, non-finite means, Box-Cox variances at and below FLT_EPSILON (no
// skewness correction).
TEST(EstimatorImage, FromStatisticsFollowsTheDefinitionsBitForBit)
{
    StatisticsPlanes stats = testing::sample_statistics(
        37, 9, 8, [](int x, int y, int c) { return 0.1f + 0.05f * float((x * 7 + y * 3 + c) % 11); },
        testing::draw_lognormal, 5);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    const float odd_mean[] = {NAN, INFINITY, -INFINITY};
    for (std::size_t i = 0; i < stats.count.size(); ++i) {
        const float r = u(rng);
        stats.count[i] = r < 0.05f ? 0.f : r < 0.1f ? 1.f : r < 0.15f ? 2.f : stats.count[i];
    }
    for (std::size_t i = 0; i < stats.mean.size(); ++i) {
        if (u(rng) < 0.04f)
            stats.mean[i] = odd_mean[int(3 * u(rng)) % 3];
        if (u(rng) < 0.05f)
            stats.bc_variance[i] = u(rng) < 0.5f ? FLT_EPSILON : 0.5f * FLT_EPSILON;
    }
    for (bool of_mean : {false, true})
        for (TestDomain domain : {TestDomain::BoxCox, TestDomain::Untransformed}) {
            StatisticsView view = stats.view();
            view.variance_of_mean = of_mean;
            const EstimatorImage est = estimators_from_statistics(view, domain);
            int untestable = 0;
            for (int y = 0; y < est.height; ++y)
                for (int x = 0; x < est.width; ++x) {
                    const float n = view.count(x, y);
                    ASSERT_TRUE(same_bits(est.count[est.index(0, x, y)], n));
                    bool testable = n >= 2;
                    float mean[3], variance[3];
                    for (int c = 0; c < 3; ++c) {
                        const float f = view.mean[c](x, y);
                        testable = testable && std::isfinite(f);
                        ASSERT_TRUE(same_bits(est.value[est.index(c, x, y)], std::isfinite(f) ? f : 0.f));
                        if (domain == TestDomain::BoxCox) {
                            const float s2 = view.bc_variance[c](x, y);
                            const float skew = s2 > FLT_EPSILON ? view.bc_moment3[c](x, y) / (6.f * s2 * n) : 0.f;
                            mean[c] = view.bc_mean[c](x, y) + skew;
                            variance[c] = s2 / n;
                        } else {
                            const float var = view.variance[c](x, y);
                            mean[c] = f;
                            variance[c] = of_mean ? var : var / n;
                        }
                        testable = testable && std::isfinite(mean[c]) && std::isfinite(variance[c]) &&
                                   variance[c] >= 0;
                    }
                    untestable += !testable;
                    for (int c = 0; c < 3; ++c) {
                        const std::size_t i = est.index(c, x, y);
                        ASSERT_TRUE(same_bits(est.test_mean[i], testable ? mean[c] : 0.f))
                            << "(" << x << ", " << y << ", " << c << ")";
                        ASSERT_TRUE(testable ? same_bits(est.test_variance[i], variance[c])
                                             : std::isnan(est.test_variance[i]))
                            << "(" << x << ", " << y << ", " << c << ")";
                    }
                }
            EXPECT_GT(untestable, 20);
            EXPECT_LT(untestable, int(est.pixels()) / 2);
        }
}

}  // namespace
}  // namespace statmc
