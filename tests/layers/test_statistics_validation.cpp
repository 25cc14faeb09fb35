#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

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

// The first look at a row compares runs of 16 pixels at once and leaves the rest to a
// pixel-by-pixel loop: a bad value at any pixel of a 37-pixel row, in any checked
// channel, with the region starting at 0 or at an odd column, is found where it is.
TEST(StatisticsValidation, EveryPixelOfARowIsChecked)
{
    const OIIO::ImageBuf valid = make_statistics_image(test::noisy_statistics(37, 3, 4, 23));
    const struct {
        const char* channel;
        float value;
    } bad[] = {{"sampleCount.Y", 0.f},
               {"R", std::numeric_limits<float>::quiet_NaN()},
               {"variance.G", -1.f},
               {"boxcoxMean.B", -3.f},
               {"boxcoxM4.B", -1.f}};
    for (int x0 : {0, 3})
        for (const auto& b : bad)
            for (int x = x0; x < 37; ++x) {
                OIIO::ImageBuf buf = valid;
                test::set_channel(buf, b.channel, x, 1, b.value);
                ValidationOptions options;
                options.roi = OIIO::ROI(x0, 37, 0, 3);
                const auto problems = problems_of(buf, options);
                ASSERT_EQ(problems.size(), 1u) << b.channel << " at x = " << x << ", from " << x0
                                               << ": " << join_messages(problems);
                EXPECT_EQ(problems[0].channel, b.channel);
                EXPECT_EQ(problems[0].x, x);
                EXPECT_EQ(problems[0].y, 1);
            }
}

// The fourth-moment relation, on values spread around its bound over many magnitudes,
// against the rule written out here in long double: M4/n < (1 − 1e-5)·m2² − 1e-30, with
// m2 = s²(n − 1)/n. Values within 1e-9 (relative) of the rule's edge, where the two
// precisions may round apart, are moved off it.
TEST(StatisticsValidation, TheFourthMomentFollowsItsRuleAcrossMagnitudes)
{
    constexpr int kW = 61, kH = 23;
    OIIO::ImageBuf buf = make_statistics_image(test::noisy_statistics(kW, kH, 4, 29));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> exponent(-30, 30), unit(0, 1);
    const double counts[] = {1, 2, 3, 4, 17, 64, 1000, 65536};
    std::size_t bad4 = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float n = float(counts[rng() % 8]);
            const float s2 = float(std::pow(10.0, exponent(rng)));
            const long double m2 = (long double)s2 * (n - 1) / n;
            // The fourth moment: ratio to m2² in [0.98, 1.02] around 1 − 1e-5.
            long double r4 = 0.98L + 0.04L * (long double)unit(rng);
            if (std::fabs(double(r4 - (1 - 1e-5L))) < 1e-9)
                r4 += 1e-8L;
            const float m4 = float(r4 * m2 * m2);
            test::set_channel(buf, "sampleCount.Y", x, y, n);
            test::set_channel(buf, "variance.R", x, y, s2);
            test::set_channel(buf, "M4.R", x, y, m4);
            bad4 += (long double)m4 < (1 - 1e-5L) * m2 * m2 - 1e-30L;
        }
    std::size_t found4 = 0;
    for (const StatisticsProblem& p : problems_of(buf))
        if (p.channel == "M4.R")
            found4 = p.pixels;
    // Both kinds of pixel are there in numbers, so either slip would show.
    EXPECT_GT(bad4, 100u);
    EXPECT_LT(bad4, std::size_t(kW * kH) - 100);
    EXPECT_EQ(found4, bad4);
}

}  // namespace
}  // namespace statmc::layers
