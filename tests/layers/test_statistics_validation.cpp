#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "statmc/layers/statistics_validation.h"
#include "test_images.h"

namespace statmc::layers {
namespace {

constexpr int kW = 16, kH = 10;

OIIO::ImageBuf valid_image()
{
    return make_statistics_image(test::noisy_statistics(kW, kH, 4, 21));
}

std::vector<StatisticsProblem> problems_of(const OIIO::ImageBuf& buf,
                                           const ValidationOptions& options = {})
{
    return validate_statistics(buf, find_statistics(buf.spec()), options);
}

TEST(StatisticsValidation, ValidStatisticsPass) { EXPECT_TRUE(problems_of(valid_image()).empty()); }

TEST(StatisticsValidation, NegativeVarianceNamesChannelPixelAndCount)
{
    OIIO::ImageBuf buf = valid_image();
    test::set_channel(buf, "variance.G", 12, 7, -0.3f);
    test::set_channel(buf, "variance.G", 1, 9, -2.f);  // later in row order
    const auto problems = problems_of(buf);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(problems[0].channel, "variance.G");
    EXPECT_EQ(problems[0].x, 12);
    EXPECT_EQ(problems[0].y, 7);
    EXPECT_EQ(problems[0].pixels, 2u);
    EXPECT_EQ(problems[0].message(),
              "variance.G: negative value -0.3 at pixel (12, 7) [2 pixels affected]");
}

TEST(StatisticsValidation, ZeroCountAndNonFiniteValues)
{
    OIIO::ImageBuf buf = valid_image();
    test::set_channel(buf, "sampleCount.Y", 3, 4, 0.f);
    test::set_channel(buf, "boxcoxMean.R", 5, 6, std::numeric_limits<float>::quiet_NaN());
    test::set_channel(buf, "B", 0, 0, std::numeric_limits<float>::infinity());
    test::set_channel(buf, "boxcoxVariance.B", 2, 2, -1.f);
    test::set_channel(buf, "boxcoxMean.G", 7, 1, -2.5f);
    const auto problems = problems_of(buf);
    EXPECT_EQ(join_messages(problems),
              "sampleCount.Y: n = 0 at pixel (3, 4) [1 pixel affected]; "
              "B: Inf at pixel (0, 0) [1 pixel affected]; "
              "boxcoxMean.R: NaN at pixel (5, 6) [1 pixel affected]; "
              "boxcoxMean.G: value -2.5 below -2, the Box-Cox minimum at pixel (7, 1) "
              "[1 pixel affected]; "
              "boxcoxVariance.B: negative value -1 at pixel (2, 2) [1 pixel affected]");

    // Left to core, non-finite values are no problem; the rest still are.
    ValidationOptions lenient;
    lenient.nonfinite_is_problem = false;
    EXPECT_EQ(problems_of(buf, lenient).size(), 3u);
}

TEST(StatisticsValidation, FourthMomentBelowTheSquaredSecondIsInconsistent)
{
    // M4/n ≥ (M2/n)² for any values: at n = 4 and s² = 2 (M2/n = 1.5), M4/n must be ≥ 2.25.
    OIIO::ImageBuf buf = valid_image();
    test::set_channel(buf, "sampleCount.Y", 6, 3, 4.f);
    test::set_channel(buf, "variance.G", 6, 3, 2.f);
    test::set_channel(buf, "M4.G", 6, 3, 2.3f);  // consistent
    test::set_channel(buf, "boxcoxVariance.R", 6, 3, 2.f);
    test::set_channel(buf, "boxcoxM4.R", 6, 3, 2.25f);  // the bound itself
    EXPECT_EQ(join_messages(problems_of(buf)), "");
    test::set_channel(buf, "M4.G", 6, 3, 2.2f);
    test::set_channel(buf, "M4.B", 1, 8, -1.f);  // negative: named once, as negative
    EXPECT_EQ(join_messages(problems_of(buf)),
              "M4.B: negative value -1 at pixel (1, 8) [1 pixel affected]; "
              "M4.G: fourth moment 2.2 below the square of the second, 2.25: inconsistent "
              "moments at pixel (6, 3) [1 pixel affected]");
}

TEST(StatisticsValidation, ACoMomentBeyondCauchySchwarzIsInconsistent)
{
    OIIO::ImageBuf buf = make_statistics_image(test::noisy_statistics(kW, kH, 4, 25, true));
    EXPECT_TRUE(problems_of(buf).empty());
    // |Σ(f − f̄)(u − ū)/n| ≤ sqrt(m2_f · m2_u), m2_f = s²(n − 1)/n, from the stored pixel.
    const double n = test::channel_value(buf, "sampleCount.Y", 3, 2);
    const double bound = std::sqrt(test::channel_value(buf, "variance.R", 3, 2) * (n - 1) / n *
                                   test::channel_value(buf, "subpixel.UU", 3, 2));
    test::set_channel(buf, "covU.R", 3, 2, float(0.999 * bound));
    EXPECT_TRUE(problems_of(buf).empty()) << join_messages(problems_of(buf));
    test::set_channel(buf, "covU.R", 3, 2, float(-1.01 * bound));
    test::set_channel(buf, "subpixel.VV", 5, 1, -0.01f);
    const auto problems = problems_of(buf);
    ASSERT_EQ(problems.size(), 2u) << join_messages(problems);
    EXPECT_EQ(problems[0].message(),
              "subpixel.VV: negative value -0.01 at pixel (5, 1) [1 pixel affected]");
    EXPECT_EQ(problems[1].channel, "covU.R");
    EXPECT_EQ(problems[1].x, 3);
    EXPECT_EQ(problems[1].y, 2);
    EXPECT_NE(problems[1].what.find("inconsistent moments"), std::string::npos);
}

TEST(StatisticsValidation, RoiLimitsTheCheckAndCoordinatesFollowTheDataWindow)
{
    OIIO::ImageBuf buf = valid_image();
    buf.set_origin(100, 50);
    test::set_channel(buf, "variance.R", 110, 55, -1.f);
    const auto all = problems_of(buf);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(all[0].x, 110);
    EXPECT_EQ(all[0].y, 55);
    ValidationOptions elsewhere;
    elsewhere.roi = OIIO::ROI(100, 105, 50, 60);
    EXPECT_TRUE(problems_of(buf, elsewhere).empty());
}

}  // namespace
}  // namespace statmc::layers
