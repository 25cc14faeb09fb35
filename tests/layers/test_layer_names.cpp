#include <gtest/gtest.h>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"

namespace statmc::layers {
namespace {

TEST(LayerNames, BeautyStatisticsAreTopLevelLayers)
{
    EXPECT_EQ(channel_name(statistic_layer("", Statistic::Mean), "R"), "R");
    EXPECT_EQ(channel_name(statistic_layer("", Statistic::Variance), "G"), "variance.G");
    EXPECT_EQ(channel_name(statistic_layer("", Statistic::BoxCoxMean), "B"), "boxcoxMean.B");
    EXPECT_EQ(channel_name(statistic_layer("", Statistic::BoxCoxVariance), "R"),
              "boxcoxVariance.R");
    EXPECT_EQ(channel_name(statistic_layer("", Statistic::BoxCoxMoment3), "R"), "boxcoxM3.R");
}

TEST(LayerNames, AovStatisticsNestTwoLevels)
{
    EXPECT_EQ(channel_name(statistic_layer("diffuse", Statistic::Mean), "R"), "diffuse.R");
    EXPECT_EQ(channel_name(statistic_layer("bounce1", Statistic::Variance), "Y"),
              "bounce1.variance.Y");
    EXPECT_EQ(channel_name(statistic_layer("bounce1", Statistic::BoxCoxMoment3), "B"),
              "bounce1.boxcoxM3.B");
}

TEST(LayerNames, DiagnosticsSitUnderTheAov)
{
    EXPECT_EQ(diagnostics_channel("", kMembersChannel), "diagnostics.members");
    EXPECT_EQ(diagnostics_channel("", kEffectiveSamplesChannel), "diagnostics.effectiveSamples");
    EXPECT_EQ(diagnostics_channel("diffuse", kMembersChannel), "diffuse.diagnostics.members");
}

TEST(LayerNames, StatisticsChannelsAreRecognised)
{
    EXPECT_TRUE(is_statistics_channel("sampleCount.Y"));
    EXPECT_TRUE(is_statistics_channel("variance.R"));
    EXPECT_TRUE(is_statistics_channel("boxcoxM3.B"));
    EXPECT_TRUE(is_statistics_channel("diffuse.variance.G", "diffuse"));
    EXPECT_FALSE(is_statistics_channel("diffuse.variance.G"));
    EXPECT_FALSE(is_statistics_channel("R"));
    EXPECT_FALSE(is_statistics_channel("albedo.R"));
    EXPECT_FALSE(is_statistics_channel("A"));
}

TEST(LayerNames, SuffixesByChannelCount)
{
    EXPECT_EQ(suffixes_for_channels(3), (std::vector<std::string>{"R", "G", "B"}));
    EXPECT_EQ(suffixes_for_channels(1), (std::vector<std::string>{"Y"}));
    EXPECT_THROW(suffixes_for_channels(2), LayerError);
}

TEST(LayerLookup, DescribesAndListsLayers)
{
    OIIO::ImageSpec spec(4, 4, 6, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B", "Variance.R", "bounce1.variance.R", "sampleCount.Y"};
    EXPECT_EQ(describe_layer("variance", colour_suffixes()),
              "variance (channels variance.R, variance.G, variance.B)");
    EXPECT_EQ(describe_layer("", colour_suffixes()), "beauty (channels R, G, B)");
    EXPECT_EQ(layers_in(spec),
              (std::vector<std::string>{"", "Variance", "bounce1.variance", "sampleCount"}));
    EXPECT_EQ(missing_layer_message(spec, "variance", colour_suffixes()),
              "missing layer variance (channels variance.R, variance.G, variance.B); the image "
              "has layers R,G,B, Variance, bounce1.variance, sampleCount; did you mean "
              "Variance?");
}

TEST(LayerLookup, RequireNamesMissingChannelsOfPartialLayer)
{
    OIIO::ImageSpec spec(4, 4, 4, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "variance.R", "variance.B"};
    try {
        require_layer(spec, "variance", colour_suffixes());
        FAIL() << "expected LayerError";
    } catch (const LayerError& e) {
        EXPECT_STREQ(e.what(), "incomplete layer variance (channels variance.R, variance.G, "
                               "variance.B): missing variance.G");
    }
    EXPECT_TRUE(optional_layer(spec, "albedo", colour_suffixes()).empty());
    EXPECT_EQ(require_layer(spec, "variance", {"R", "B"}), (std::vector<int>{2, 3}));
}

}  // namespace
}  // namespace statmc::layers

namespace statmc::layers {
namespace {

TEST(LayerNames, BounceAovsAreOneNamePartWithoutLeadingDigit)
{
    EXPECT_EQ(bounce_aov(BounceQuantity::Luminance, 0), "bounce0L");
    EXPECT_EQ(bounce_aov(BounceQuantity::Luminance, 12), "bounce12L");
    EXPECT_EQ(bounce_aov(BounceQuantity::LightWins, 3), "bounce3LightWins");
    EXPECT_EQ(bounce_aov(BounceQuantity::BsdfWins, 5), "bounce5BsdfWins");
    // Two levels with the statistic: <aov>.<stat>.<channel>.
    EXPECT_EQ(channel_name(statistic_layer(bounce_aov(BounceQuantity::Luminance, 2),
                                           Statistic::BoxCoxMoment3),
                           "Y"),
              "bounce2L.boxcoxM3.Y");
    EXPECT_THROW(bounce_aov(BounceQuantity::Luminance, -1), LayerError);
    for (int b = 0; b < 40; ++b)
        for (auto q :
             {BounceQuantity::Luminance, BounceQuantity::LightWins, BounceQuantity::BsdfWins})
            EXPECT_TRUE(is_valid_aov_name(bounce_aov(q, b)));
}

TEST(LayerNames, AovNamesNeedNoLeadingDigitDotOrSpace)
{
    EXPECT_TRUE(is_valid_aov_name("diffuse"));
    EXPECT_FALSE(is_valid_aov_name(""));
    EXPECT_FALSE(is_valid_aov_name("1bounce"));
    EXPECT_FALSE(is_valid_aov_name("bounce1.L"));
    EXPECT_FALSE(is_valid_aov_name("bounce 1"));
}

}  // namespace
}  // namespace statmc::layers

namespace statmc::layers {
namespace {

TEST(LayerNames, StatisticsOfAnyAovAreRecognisedAndMeansAreNot)
{
    for (const char* statistic :
         {"variance.R", "boxcoxM3.B", "sampleCount.Y", "diffuse.variance.G", "bounce1L.M4.Y",
          "spec.boxcoxMean.R", "albedoVariance.Y", "normalVariance.Y"})
        EXPECT_TRUE(is_any_statistics_channel(statistic)) << statistic;
    for (const char* mean : {"R", "A", "diffuse.R", "albedo.G", "normal.X", "depth.Z", "bounce1L.Y",
                             "diagnostics.members", "ViewLayer.Combined.R", "subpixel.UV"})
        EXPECT_FALSE(is_any_statistics_channel(mean)) << mean;
}

}  // namespace
}  // namespace statmc::layers
