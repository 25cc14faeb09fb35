// EstimatorImage's own rules: which pixels the test may use.
#include <gtest/gtest.h>

#include "estimator_fixtures.h"

namespace statmc {
namespace {

TEST(EstimatorImage, TestableRowIsTestableOfEachPixel)
{
    // Every way a pixel can be untestable (n < 2, a NaN or infinite mean or variance, a
    // negative variance), beside -0 and 0 variances, which are testable.
    const EstimatorImage est = testing::odd_estimators(TestDomain::BoxCox, 0, 23);
    int untestable = 0;
    std::vector<std::uint8_t> row(est.width);
    for (int y = 0; y < est.height; ++y) {
        est.testable_row(y, row.data());
        for (int x = 0; x < est.width; ++x) {
            ASSERT_EQ(row[x], est.testable(x, y) ? 1 : 0) << "(" << x << ", " << y << ")";
            untestable += !row[x];
        }
    }
    EXPECT_GT(untestable, est.width);  // the fixture holds plenty of each kind
    EXPECT_LT(untestable, int(est.pixels()) / 2);
}

}  // namespace
}  // namespace statmc
