// EstimatorImage's own rules: which pixels the test may use.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "estimator_fixtures.h"

namespace statmc {
namespace {

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

}  // namespace
}  // namespace statmc
