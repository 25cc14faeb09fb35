// The layer contract end to end: planes -> ImageBuf -> EXR file -> ImageBuf -> view.
#include <array>

#include <OpenImageIO/half.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "statmc/layers/float_pixels.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/statistics_layers.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::layers {
namespace {

using test::same_bits;

constexpr int kW = 13, kH = 9;

// Every pixel of every plane the two views share is bitwise equal; a plane present in
// one view must be present in the other.
void expect_same_planes(const StatisticsView& expected, const StatisticsView& got)
{
    ASSERT_EQ(got.width, expected.width);
    ASSERT_EQ(got.height, expected.height);
    ASSERT_EQ(got.channels, expected.channels);
    EXPECT_EQ(got.variance_of_mean, expected.variance_of_mean);
    int compared = 0;
    auto compare = [&](const ConstPlane& e, const ConstPlane& g, const char* what, int c) {
        ASSERT_EQ(bool(e), bool(g)) << what << " channel " << c;
        if (!e)
            return;
        for (int y = 0; y < expected.height; ++y)
            for (int x = 0; x < expected.width; ++x)
                ASSERT_TRUE(same_bits(e(x, y), g(x, y)))
                    << what << "[" << c << "] at (" << x << ", " << y << "): " << e(x, y) << " vs "
                    << g(x, y);
        ++compared;
    };
    compare(expected.count, got.count, "count", 0);
    for (int c = 0; c < expected.channels; ++c) {
        compare(expected.mean[c], got.mean[c], "mean", c);
        compare(expected.variance[c], got.variance[c], "variance", c);
        compare(expected.bc_mean[c], got.bc_mean[c], "bc_mean", c);
        compare(expected.bc_variance[c], got.bc_variance[c], "bc_variance", c);
        compare(expected.bc_moment3[c], got.bc_moment3[c], "bc_moment3", c);
        compare(expected.moment3[c], got.moment3[c], "moment3", c);
        compare(expected.moment4[c], got.moment4[c], "moment4", c);
        compare(expected.bc_moment4[c], got.bc_moment4[c], "bc_moment4", c);
    }
    EXPECT_GT(compared, 0);
}

TEST(StatisticsLayers, ImageHasTheContractsChannelsAndAttributes)
{
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 8, 1);
    StatisticsMetadata meta;
    meta.spp = 64;
    meta.seed = 7;
    const test::GuideData guides = test::make_guides(kW, kH, 2);
    const OIIO::ImageBuf buf = make_statistics_image(stats, meta, guides.planes());
    const OIIO::ImageSpec& spec = buf.spec();
    EXPECT_EQ(spec.channelnames, (std::vector<std::string>{"R",
                                                           "G",
                                                           "B",
                                                           "sampleCount.Y",
                                                           "variance.R",
                                                           "variance.G",
                                                           "variance.B",
                                                           "boxcoxMean.R",
                                                           "boxcoxMean.G",
                                                           "boxcoxMean.B",
                                                           "boxcoxVariance.R",
                                                           "boxcoxVariance.G",
                                                           "boxcoxVariance.B",
                                                           "boxcoxM3.R",
                                                           "boxcoxM3.G",
                                                           "boxcoxM3.B",
                                                           "M3.R",
                                                           "M3.G",
                                                           "M3.B",
                                                           "M4.R",
                                                           "M4.G",
                                                           "M4.B",
                                                           "boxcoxM4.R",
                                                           "boxcoxM4.G",
                                                           "boxcoxM4.B",
                                                           "albedo.R",
                                                           "albedo.G",
                                                           "albedo.B",
                                                           "normal.X",
                                                           "normal.Y",
                                                           "normal.Z",
                                                           "depth.Z"}));
    EXPECT_EQ(spec.alpha_channel, -1);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    EXPECT_EQ(spec.get_int_attribute("statmc:formatVersion"), 2);
    EXPECT_EQ(spec.get_float_attribute("statmc:boxcoxLambda"), 0.5f);
    EXPECT_EQ(spec.get_string_attribute("statmc:variance"), "sample");
    EXPECT_EQ(spec.get_int_attribute("statmc:spp"), 64);
    EXPECT_EQ(spec.get_int_attribute("statmc:seed"), 7);
    EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
    EXPECT_EQ(test::channel_value(buf, "depth.Z", 3, 4), 5.f);  // 1 + y
}

TEST(StatisticsLayers, FileRoundTripIsBitwiseExact)
{
    test::TempDir dir;
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 8, 3);
    StatisticsMetadata meta;
    meta.spp = 8;
    meta.seed = 3;
    test::write_exr(make_statistics_image(stats, meta), dir.file("stats.exr"));

    // What the file itself says, before OIIO's ImageBuf reorders anything.
    auto in = OIIO::ImageInput::open(dir.file("stats.exr"));
    ASSERT_TRUE(in);
    const OIIO::ImageSpec file_spec = in->spec();
    EXPECT_EQ(file_spec.format, OIIO::TypeDesc::FLOAT);
    EXPECT_TRUE(file_spec.channelformats.empty());
    EXPECT_EQ(file_spec.tile_width, 0);  // scanline
    EXPECT_EQ(file_spec.get_string_attribute("compression"), "zip");
    EXPECT_EQ(file_spec.get_int_attribute("statmc:formatVersion"), 2);
    EXPECT_EQ(file_spec.get_float_attribute("statmc:boxcoxLambda"), 0.5f);
    EXPECT_EQ(file_spec.get_string_attribute("statmc:variance"), "sample");
    EXPECT_EQ(file_spec.get_int_attribute("statmc:spp"), 8);
    EXPECT_EQ(file_spec.get_int_attribute("statmc:seed"), 3);
    in.reset();

    const OIIO::ImageBuf back = test::read_exr(dir.file("stats.exr"));
    expect_same_planes(stats.view(), read_statistics(back));
}

TEST(StatisticsLayers, ShuffledChannelOrderIsReadByName)
{
    test::TempDir dir;
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 6, 4);
    const OIIO::ImageBuf shuffled = test::reversed_channels(make_statistics_image(stats));
    ASSERT_EQ(shuffled.spec().channelnames.front(), "boxcoxM4.B");
    // In memory, in the reversed order...
    expect_same_planes(stats.view(), read_statistics(shuffled));
    // ...and through a file written in that order.
    test::write_exr(shuffled, dir.file("shuffled.exr"));
    expect_same_planes(stats.view(), read_statistics(test::read_exr(dir.file("shuffled.exr"))));
}

TEST(StatisticsLayers, AovPrefixedStatisticsRoundTrip)
{
    test::TempDir dir;
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 5, 5);
    StatisticsMetadata meta;
    meta.aov = "diffuse";
    test::write_exr(make_statistics_image(stats, meta), dir.file("aov.exr"));
    const OIIO::ImageBuf back = test::read_exr(dir.file("aov.exr"));
    EXPECT_GE(back.spec().channelindex("diffuse.variance.G"), 0);
    EXPECT_GE(back.spec().channelindex("diffuse.boxcoxM3.B"), 0);
    expect_same_planes(stats.view(), read_statistics(back, "diffuse"));
    EXPECT_THROW(read_statistics(back), LayerError);  // no beauty R,G,B
}

TEST(StatisticsLayers, ExtraAovsShareTheCountAndRoundTrip)
{
    // A beauty plus two AOVs in one image: a colour one and a scalar (Y) one, as the
    // renderer's per-bounce layers are; each is read back bitwise under its prefix.
    test::TempDir dir;
    const StatisticsPlanes beauty = test::noisy_statistics(kW, kH, 8, 11);
    const StatisticsPlanes colour = test::noisy_statistics(kW, kH, 8, 12);  // same counts
    const StatisticsPlanes scalar_src = test::noisy_statistics(kW, kH, 8, 13);
    StatisticsView scalar = scalar_src.view();
    scalar.channels = 1;
    const std::vector<AovStatistics> aovs = {{"diffuse", colour.view()}, {"bounce2L", scalar}};
    test::write_exr(make_statistics_image(beauty.view(), {}, {}, aovs), dir.file("aovs.exr"));
    const OIIO::ImageBuf back = test::read_exr(dir.file("aovs.exr"));
    EXPECT_GE(back.spec().channelindex("bounce2L.Y"), 0);
    EXPECT_GE(back.spec().channelindex("bounce2L.boxcoxM3.Y"), 0);
    EXPECT_LT(back.spec().channelindex("bounce2L.R"), 0);
    // beauty + count, colour AOV, scalar AOV: 6 statistics and 3 higher moments a channel
    EXPECT_EQ(back.spec().nchannels, 25 + 24 + 8);
    expect_same_planes(beauty.view(), read_statistics(back));
    expect_same_planes(colour.view(), read_statistics(back, "diffuse"));
    expect_same_planes(scalar, read_statistics(back, "bounce2L"));
}

TEST(StatisticsLayers, ExtraAovsAreChecked)
{
    const StatisticsPlanes beauty = test::noisy_statistics(kW, kH, 8, 11);
    const StatisticsPlanes other = test::noisy_statistics(kW, kH, 8, 12);
    const StatisticsPlanes more = test::noisy_statistics(kW, kH, 9, 12);  // counts differ
    const StatisticsPlanes small = test::noisy_statistics(kW - 1, kH, 8, 12);
    auto make = [&](std::vector<AovStatistics> aovs) {
        return make_statistics_image(beauty.view(), {}, {}, aovs);
    };
    EXPECT_NO_THROW(make({{"bounce0L", other.view()}}));
    EXPECT_THROW(make({{"bounce0L", more.view()}}), LayerError);
    EXPECT_THROW(make({{"bounce0L", small.view()}}), LayerError);
    EXPECT_THROW(make({{"0bounce", other.view()}}), LayerError);
    EXPECT_THROW(make({{"bounce.L", other.view()}}), LayerError);
    EXPECT_THROW(make({{"bounce0L", other.view()}, {"bounce0L", other.view()}}), LayerError);
}

TEST(StatisticsLayers, MeanAndVarianceOnlyIsAVarianceAov)
{
    const StatisticsPlanes stats = test::variance_aov(test::noisy_statistics(kW, kH, 5, 6));
    const OIIO::ImageBuf buf = make_statistics_image(stats);
    EXPECT_EQ(buf.spec().nchannels, 7);
    EXPECT_FALSE(buf.spec().find_attribute("statmc:boxcoxLambda"));
    const StatisticsChannels ch = find_statistics(buf.spec());
    EXPECT_TRUE(ch.has(Statistic::Variance));
    EXPECT_FALSE(ch.has_box_cox());
    expect_same_planes(stats.view(), read_statistics(buf));
}

TEST(StatisticsLayers, VarianceOfTheMeanAttributeSetsTheFlag)
{
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 5, 7);
    StatisticsView view = stats.view();
    view.variance_of_mean = true;
    const OIIO::ImageBuf buf = make_statistics_image(view);
    EXPECT_EQ(buf.spec().get_string_attribute("statmc:variance"), "mean");
    EXPECT_TRUE(read_statistics(buf).variance_of_mean);
}

TEST(StatisticsLayers, HalfPixelsAreConvertedToFloat)
{
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 5, 8);
    const OIIO::ImageBuf buf = make_statistics_image(stats);
    const OIIO::ImageBuf half = buf.copy(OIIO::TypeDesc::HALF);
    EXPECT_FALSE(has_local_float_pixels(half));
    EXPECT_THROW(read_statistics(half), LayerError);
    OIIO::ImageBuf scratch;
    const OIIO::ImageBuf& floats = local_float_pixels(half, scratch);
    EXPECT_EQ(&floats, &scratch);
    const StatisticsView view = read_statistics(floats);
    // Values are the half roundings of the originals.
    EXPECT_EQ(view.mean[1](2, 3), float(Imath::half(stats.view().mean[1](2, 3))));
    EXPECT_EQ(&local_float_pixels(buf, scratch), &buf);  // already float: no copy
}

std::string error_of(const OIIO::ImageBuf& buf)
{
    try {
        find_statistics(buf.spec());
    } catch (const LayerError& e) {
        return e.what();
    }
    return "no error";
}

TEST(StatisticsLayers, AMissingSampleCountSaysWhatToDo)
{
    const OIIO::ImageBuf full = make_statistics_image(test::noisy_statistics(kW, kH, 5, 9));
    // A variance AOV without its count: append the count.
    EXPECT_NE(error_of(test::without_channels(full, {"sampleCount.Y"}))
                  .find("append it as a constant layer"),
              std::string::npos);
    // A plain render (only R, G, B): take passes.
    std::vector<std::string> statistics;
    for (const std::string& name : full.spec().channelnames)
        if (name != "R" && name != "G" && name != "B")
            statistics.push_back(name);
    const std::string plain = error_of(test::without_channels(full, statistics));
    EXPECT_EQ(plain.rfind("missing layer sampleCount (channels sampleCount.Y); this looks like a "
                          "plain render",
                          0),
              0u)
        << plain;
    EXPECT_NE(plain.find("--passes"), std::string::npos);
}

TEST(StatisticsLayers, MissingLayersAreNamed)
{
    const OIIO::ImageBuf full = make_statistics_image(test::noisy_statistics(kW, kH, 5, 9));
    EXPECT_EQ(error_of(test::without_channels(full, {"sampleCount.Y"}))
                  .rfind("missing layer sampleCount (channels sampleCount.Y)", 0),
              0u);
    EXPECT_EQ(error_of(test::without_channels(full, {"R", "G", "B"}))
                  .rfind("missing layer beauty (channels R, G, B)", 0),
              0u);
    EXPECT_EQ(error_of(test::without_channels(full, {"variance.G"})),
              "incomplete layer variance (channels variance.R, variance.G, variance.B): "
              "missing variance.G");
    EXPECT_EQ(error_of(test::without_channels(full, {"boxcoxM3.R", "boxcoxM3.G", "boxcoxM3.B"}))
                  .rfind("incomplete Box-Cox statistics: missing layer boxcoxM3 (channels "
                         "boxcoxM3.R, boxcoxM3.G, boxcoxM3.B)",
                         0),
              0u);
    // Without the variance the reader still finds the rest; require_statistic names it.
    const OIIO::ImageBuf no_variance = test::renamed_channels(full, "variance", "Variance");
    const StatisticsChannels ch = find_statistics(no_variance.spec());
    EXPECT_FALSE(ch.has(Statistic::Variance));
    try {
        require_statistic(no_variance.spec(), ch, Statistic::Variance);
        FAIL() << "expected LayerError";
    } catch (const LayerError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("missing layer variance (channels variance.R, variance.G, "
                            "variance.B)"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("did you mean Variance?"), std::string::npos) << what;
    }
}

TEST(StatisticsLayers, HeaderAttributesAreChecked)
{
    OIIO::ImageBuf buf = make_statistics_image(test::noisy_statistics(kW, kH, 5, 10));
    buf.specmod().attribute("statmc:variance", "stddev");
    EXPECT_EQ(error_of(buf), "statmc:variance must be \"sample\" or \"mean\", got \"stddev\"");
    buf.specmod().attribute("statmc:variance", "sample");
    buf.specmod().attribute("statmc:boxcoxLambda", 0.25f);
    EXPECT_EQ(error_of(buf),
              "statmc:boxcoxLambda is 0.25; the Box-Cox statistics must use lambda 0.5");
    buf.specmod().attribute("statmc:boxcoxLambda", 0.5f);
    buf.specmod().attribute("statmc:formatVersion", 3);
    EXPECT_EQ(error_of(buf), "statmc:formatVersion is 3; this build reads versions 1 to 2");
    buf.specmod().attribute("statmc:formatVersion", 1);  // version 1 is version 2 less the moments
    EXPECT_EQ(error_of(buf), "no error");
    buf.specmod().erase_attribute("statmc:formatVersion");
    EXPECT_EQ(error_of(buf), "no error");  // other renderers write no statmc: attributes
}

TEST(StatisticsLayers, VersionOneFilesReadWithoutTheHigherMoments)
{
    // A file as version 1 wrote it: no M3, M4 or boxcoxM4, formatVersion 1.
    test::TempDir dir;
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 6, 21);
    OIIO::ImageBuf v1 = test::without_channels(
        make_statistics_image(stats),
        {"M3.R", "M3.G", "M3.B", "M4.R", "M4.G", "M4.B", "boxcoxM4.R", "boxcoxM4.G", "boxcoxM4.B"});
    v1.specmod().attribute("statmc:formatVersion", 1);
    test::write_exr(v1, dir.file("v1.exr"));
    const OIIO::ImageBuf back = test::read_exr(dir.file("v1.exr"));
    const StatisticsChannels ch = find_statistics(back.spec());
    EXPECT_TRUE(ch.has_box_cox());
    EXPECT_FALSE(ch.has(Statistic::Moment4));
    EXPECT_FALSE(ch.has(Statistic::BoxCoxMoment4));
    const StatisticsView view = read_statistics(back);
    EXPECT_FALSE(view.has_moments());
    EXPECT_FALSE(view.has_box_cox_moment4());
    StatisticsPlanes without = stats;
    without.moment3.clear(), without.moment4.clear(), without.bc_moment4.clear();
    expect_same_planes(without.view(), view);
}

TEST(StatisticsLayers, HigherMomentsComeWhole)
{
    const OIIO::ImageBuf full = make_statistics_image(test::noisy_statistics(kW, kH, 5, 22));
    EXPECT_EQ(
        error_of(test::without_channels(full, {"M4.R", "M4.G", "M4.B"}))
            .rfind("incomplete higher moments: missing layer M4 (channels M4.R, M4.G, M4.B)", 0),
        0u);
    // Without the variance they extend, M3 and M4 are not read: the view has no moments.
    const OIIO::ImageBuf no_variance =
        test::without_channels(full, {"variance.R", "variance.G", "variance.B"});
    EXPECT_FALSE(read_statistics(no_variance).has_moments());
    EXPECT_TRUE(read_statistics(no_variance).has_box_cox_moment4());
}

TEST(StatisticsLayers, AnOlderFilesPositionLayersAreOtherChannels)
{
    // Format version 2 files from statmc-render carry sub-pixel position moments, which no
    // version reads any more: they are neither statistics nor checked.
    const StatisticsPlanes stats = test::noisy_statistics(kW, kH, 6, 23);
    const OIIO::ImageBuf older = test::with_retired_position_layers(make_statistics_image(stats));
    EXPECT_EQ(error_of(older), "no error");
    expect_same_planes(stats.view(), read_statistics(older));
    for (const char* name : {"subpixel.U", "subpixel.UU", "covU.R", "boxcoxCovV.B"})
        EXPECT_FALSE(is_statistics_channel(name)) << name;
}

TEST(StatisticsLayers, GuidesAreFoundWithEitherSuffixSet)
{
    const test::GuideData guides = test::make_guides(kW, kH, 11);
    const OIIO::ImageBuf buf =
        make_statistics_image(test::noisy_statistics(kW, kH, 5, 11), {}, guides.planes());
    const std::vector<int> albedo = find_guide_layer(buf.spec(), "albedo", true);
    ASSERT_EQ(albedo.size(), 3u);
    EXPECT_EQ(buf.spec().channelnames[albedo[2]], "albedo.B");
    const OIIO::ImageBuf arnold = test::renamed_channels(buf, "normal", "N");
    // N.X/Y/Z found under its own name; a normal stored as N.R/G/B would be found too.
    EXPECT_EQ(find_guide_layer(arnold.spec(), "N", false).size(), 3u);
    EXPECT_TRUE(find_guide_layer(arnold.spec(), "normal", false).empty());
    const std::array<ConstPlane, 3> planes = guide_planes(buf, albedo);
    EXPECT_EQ(planes[1](4, 5), guides.albedo[1 * kW * kH + 5 * kW + 4]);
    try {
        require_guide_layer(arnold.spec(), "normal", false);
        FAIL() << "expected LayerError";
    } catch (const LayerError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(
                      "missing guide layer normal (channels normal.X, normal.Y, normal.Z)", 0),
                  0u)
            << e.what();
    }
    EXPECT_THROW(find_guide_layer(test::without_channels(buf, {"albedo.G"}).spec(), "albedo", true),
                 LayerError);
}

}  // namespace
}  // namespace statmc::layers
