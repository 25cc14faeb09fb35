// The denoise operator must give exactly what core's filter gives on the same
// statistics, and touch nothing else.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "statmc/core/context_channel.h"
#include "statmc/core/radius_ladder.h"
#include "statmc/core/variance_filter.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/layers/view_window.h"
#include "test_images.h"

namespace statmc {
namespace {

using test::channel_value;
using test::same_bits;

constexpr int kW = 37, kH = 23;  // odd sizes: SIMD chunks straddle the edges

DenoiseOptions small_filter()
{
    DenoiseOptions o;
    o.radius = 5;
    o.alpha = 0.01;
    o.sigma_spatial = 4.f;
    return o;
}

// The classic filter (no radius ladder), which core's filter() gives directly.
DenoiseImageOptions options(GuideUse guides = GuideUse::Off)
{
    DenoiseImageOptions o = DenoiseImageOptions::classic();
    o.filter = small_filter();
    o.guides.albedo = o.guides.normal = guides;
    return o;
}

struct Frame {
    StatisticsPlanes stats = test::noisy_statistics(kW, kH, 8, 42);
    test::GuideData guides = test::make_guides(kW, kH, 43);
    OIIO::ImageBuf image = layers::make_statistics_image(stats, {}, guides.planes());
};

// R,G,B of `out` equal `expected` (dense, channel-major over the image) everywhere.
void expect_rgb_equals(const OIIO::ImageBuf& out, const std::vector<float>& expected)
{
    const std::size_t n = std::size_t(kW) * kH;
    const char* names[3] = {"R", "G", "B"};
    const int x0 = out.spec().x, y0 = out.spec().y;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float e = expected[c * n + std::size_t(y) * kW + x];
                const float g = channel_value(out, names[c], x0 + x, y0 + y);
                ASSERT_TRUE(same_bits(e, g))
                    << names[c] << " at (" << x << ", " << y << "): " << g << " vs " << e;
            }
}

// The filter must actually have changed something, or equality proves little.
std::size_t changed_pixels(const OIIO::ImageBuf& out, const OIIO::ImageBuf& in)
{
    std::size_t changed = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            changed += !same_bits(channel_value(out, "G", x, y), channel_value(in, "G", x, y));
    return changed;
}

TEST(DenoiseOperator, BoxCoxStatisticsMatchCoreFilterBitwise)
{
    Frame f;
    OIIO::ImageBuf out;
    ASSERT_TRUE(denoise(out, f.image, options())) << out.geterror();
    expect_rgb_equals(out,
                      test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter()));
    EXPECT_GT(changed_pixels(out, f.image), std::size_t(kW * kH / 2));
    EXPECT_EQ(out.spec().get_int_attribute("statmc:denoised"), 1);
}

TEST(DenoiseOperator, VarianceAovUsesTheUntransformedTest)
{
    Frame f;
    const StatisticsPlanes plain = test::variance_aov(f.stats);
    const OIIO::ImageBuf image = layers::make_statistics_image(plain);
    const OIIO::ImageBuf out = denoise(image, options());
    ASSERT_FALSE(out.has_error()) << out.geterror();
    const auto expected =
        test::core_filtered(plain.view(), TestDomain::Untransformed, {}, small_filter());
    expect_rgb_equals(out, expected);
    // Forcing the untransformed test on full statistics gives the same.
    DenoiseImageOptions forced = options();
    forced.test = TestDomainChoice::Untransformed;
    expect_rgb_equals(denoise(f.image, forced), expected);
    // And the two domains really differ on this data.
    const auto boxcox = test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter());
    EXPECT_NE(boxcox, expected);
}

TEST(DenoiseOperator, VarianceOfTheMeanIsHonoured)
{
    Frame f;
    StatisticsPlanes plain = test::variance_aov(f.stats);
    // Store s²/n and say so: the test must see the same variance of the mean.
    for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < plain.count.size(); ++i)
            plain.variance[c * plain.count.size() + i] /= plain.count[i];
    StatisticsView view = plain.view();
    view.variance_of_mean = true;
    const OIIO::ImageBuf out = denoise(layers::make_statistics_image(view), options());
    ASSERT_FALSE(out.has_error()) << out.geterror();
    expect_rgb_equals(out,
                      test::core_filtered(view, TestDomain::Untransformed, {}, small_filter()));
}

TEST(DenoiseOperator, RequestedGuidesAreUsed)
{
    Frame f;
    const auto expected = test::core_filtered(f.stats.view(), TestDomain::BoxCox,
                                              f.guides.planes().core(), small_filter());
    OIIO::ImageBuf out;
    ASSERT_TRUE(denoise(out, f.image, options(GuideUse::Required))) << out.geterror();
    expect_rgb_equals(out, expected);
    // Auto finds them too; without guides the result differs.
    expect_rgb_equals(denoise(f.image, options(GuideUse::Auto)), expected);
    EXPECT_NE(expected,
              test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter()));
}

TEST(DenoiseOperator, OnlyTheAlbedoGuideWhenOnlyItIsAsked)
{
    Frame f;
    DenoiseImageOptions opt = options(GuideUse::Off);
    opt.guides.albedo = GuideUse::Required;
    Guides albedo_only;
    albedo_only.albedo = f.guides.planes().albedo;
    expect_rgb_equals(denoise(f.image, opt), test::core_filtered(f.stats.view(), TestDomain::BoxCox,
                                                                 albedo_only, small_filter()));
}

TEST(DenoiseOperator, MissingRequiredGuideIsAnError)
{
    Frame f;
    const OIIO::ImageBuf no_albedo =
        test::without_channels(f.image, {"albedo.R", "albedo.G", "albedo.B"});
    OIIO::ImageBuf out;
    EXPECT_FALSE(denoise(out, no_albedo, options(GuideUse::Required)));
    EXPECT_EQ(out.geterror().rfind(
                  "missing guide layer albedo (channels albedo.R, albedo.G, albedo.B)", 0),
              0u);
    // Auto quietly goes without it and uses the normal alone.
    Guides normal_only;
    normal_only.normal = f.guides.planes().normal;
    expect_rgb_equals(
        denoise(no_albedo, options(GuideUse::Auto)),
        test::core_filtered(f.stats.view(), TestDomain::BoxCox, normal_only, small_filter()));
    // A renamed guide layer is found under its new name.
    DenoiseImageOptions renamed = options(GuideUse::Required);
    renamed.guides.normal_layer = "N";
    expect_rgb_equals(denoise(test::renamed_channels(f.image, "normal", "N"), renamed),
                      test::core_filtered(f.stats.view(), TestDomain::BoxCox,
                                          f.guides.planes().core(), small_filter()));
}

TEST(DenoiseOperator, RoiChangesOnlyItsPixelsAndReadsNeighboursOutsideIt)
{
    Frame f;
    const auto full = test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter());
    const OIIO::ROI roi(10, 21, 4, 15);
    OIIO::ImageBuf out;
    ASSERT_TRUE(denoise(out, f.image, options(), roi)) << out.geterror();
    const std::size_t n = std::size_t(kW) * kH;
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float got = channel_value(out, names[c], x, y);
                const bool inside = roi.contains(x, y);
                const float want = inside ? full[c * n + std::size_t(y) * kW + x]
                                          : channel_value(f.image, names[c], x, y);
                ASSERT_TRUE(same_bits(got, want))
                    << names[c] << " at (" << x << ", " << y << ") inside=" << inside;
            }
}

// Dense R,G,B planes over the frame, into `data` (channel-major).
std::vector<Plane> rgb_planes(std::vector<float>& data)
{
    std::vector<Plane> planes;
    for (int c = 0; c < 3; ++c)
        planes.push_back(dense_plane(data.data() + std::size_t(c) * kW * kH, kW));
    return planes;
}

// A run of `o` over a ROI gives the full run's pixels inside it: the operator reads every
// halo its stages need.
void expect_roi_matches_full(const OIIO::ImageBuf& in, const DenoiseImageOptions& o,
                             const OIIO::ImageBuf& full)
{
    const OIIO::ROI roi(10, 21, 4, 15);
    OIIO::ImageBuf part;
    ASSERT_TRUE(denoise(part, in, o, roi)) << part.geterror();
    for (int y = roi.ybegin; y < roi.yend; ++y)
        for (int x = roi.xbegin; x < roi.xend; ++x)
            for (const char* c : {"R", "G", "B"})
                ASSERT_TRUE(same_bits(channel_value(part, c, x, y), channel_value(full, c, x, y)))
                    << c << " at (" << x << ", " << y << ")";
}

TEST(DenoiseOperator, IciIsCoresRadiusLadderAndRoiSafe)
{
    Frame f;
    DenoiseImageOptions o = options();
    o.stages.radius_ladder = true;
    o.stages.ladder = DenoiseImageOptions{}.stages.ladder;
    o.stages.ladder.alpha = 0.05;
    OIIO::ImageBuf out;
    ASSERT_TRUE(denoise(out, f.image, o)) << out.geterror();
    const EstimatorImage est = estimators_from_statistics(f.stats.view(), TestDomain::BoxCox);
    std::vector<float> expected(est.value.size());
    const std::vector<Plane> planes = rgb_planes(expected);
    filter_with_radius_ladder(f.stats.view(), est, {}, small_filter(), planes, o.stages.ladder);
    expect_rgb_equals(out, expected);
    EXPECT_NE(expected, test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter()))
        << "no pixel took a smaller radius";
    expect_roi_matches_full(f.image, o, out);
}

// The default method in core's terms, on `f` without guides: the classic filter with the
// context test, each pixel at its ICI radius among `radii` on moderated variances.
std::vector<float> default_in_core(const Frame& f, const std::vector<int>& radii)
{
    const EstimatorImage est =
        with_context(estimators_from_statistics(f.stats.view(), TestDomain::BoxCox), /*green*/ 1, 1,
                     small_filter().firefly_ratio);
    std::vector<float> expected(est.pixels() * 3);
    RadiusLadderOptions ladder;
    ladder.radii = radii;
    ladder.alpha = 0.005;
    ladder.variance.prior_dof = 16;
    ladder.variance.prior_alpha = 0.05;
    ladder.energy = {3, 0.005};
    ladder.residual = {3, 0.005};
    filter_with_radius_ladder(f.stats.view(), est, {}, small_filter(), rgb_planes(expected),
                              ladder);
    return expected;
}

TEST(DenoiseOperator, TheDefaultIsTheClassicFilterWithTheModeratedLadderAndTheContextTest)
{
    Frame f;
    DenoiseImageOptions o;  // the default method
    o.filter = small_filter();
    o.guides.albedo = o.guides.normal = GuideUse::Off;
    const OIIO::ImageBuf out = denoise(f.image, o);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_EQ(out.spec().get_string_attribute("statmc:denoiseSkipped"), "");
    expect_rgb_equals(out, default_in_core(f, {1, 2, 3, 5, 8, 12, 20}));
}

TEST(DenoiseOperator, TheLaddersRungsAreTheMethods)
{
    Frame f;
    DenoiseImageOptions o;
    o.filter = small_filter();
    o.guides.albedo = o.guides.normal = GuideUse::Off;
    o.stages.ladder.radii = {2};  // with radius 5: rungs 2 and 5
    const OIIO::ImageBuf out = denoise(f.image, o);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    const std::vector<float> expected = default_in_core(f, {2});
    expect_rgb_equals(out, expected);
    EXPECT_NE(expected, default_in_core(f, {1, 2, 3}))
        << "the rungs made no difference on this frame: the test would not see them";
}

TEST(DenoiseOperator, TheDefaultsLadderNeedsNoFourthMomentAndSaysWhatItLeavesOut)
{
    Frame f;
    DenoiseImageOptions o;
    o.filter = small_filter();
    o.guides.albedo = o.guides.normal = GuideUse::Off;
    DenoiseImageOptions classic = options();
    // A format-1 file: no M3/M4. The default's ladder moderates each pixel's own variance,
    // which needs neither, so it runs, and gives the bits it gives with them.
    const OIIO::ImageBuf v1 =
        test::without_channels(f.image, {"M3.R", "M3.G", "M3.B", "M4.R", "M4.G", "M4.B"});
    const OIIO::ImageBuf out = denoise(v1, o);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_EQ(out.spec().get_string_attribute("statmc:denoiseSkipped"), "");
    const OIIO::ImageBuf with_moments = denoise(f.image, o);
    ASSERT_FALSE(with_moments.has_error()) << with_moments.geterror();
    const int x0 = out.spec().x, y0 = out.spec().y;
    for (const char* channel : {"R", "G", "B"})
        for (int y = y0; y < y0 + kH; ++y)
            for (int x = x0; x < x0 + kW; ++x)
                ASSERT_TRUE(same_bits(channel_value(out, channel, x, y),
                                      channel_value(with_moments, channel, x, y)))
                    << channel << " at (" << x << ", " << y << ")";
    // Without the variance layer the ladder is left out, and the note says why.
    const OIIO::ImageBuf no_variance =
        denoise(test::without_channels(f.image, {"variance.R", "variance.G", "variance.B"}), o);
    ASSERT_FALSE(no_variance.has_error()) << no_variance.geterror();
    EXPECT_EQ(no_variance.spec().get_string_attribute("statmc:denoiseSkipped"),
              "ici (needs the variance layer)");
    expect_rgb_equals(no_variance, test::core_filtered(f.stats.view(), TestDomain::BoxCox, {},
                                                       classic.filter, o.stages.context_radius));
    // Diagnostics describe one radius per pixel, so the ladder steps aside for them too.
    o.diagnostics = true;
    const OIIO::ImageBuf with_diagnostics = denoise(f.image, o);
    ASSERT_FALSE(with_diagnostics.has_error()) << with_diagnostics.geterror();
    EXPECT_NE(
        with_diagnostics.spec().get_string_attribute("statmc:denoiseSkipped").find("diagnostics"),
        std::string::npos);
}

TEST(DenoiseOperator, MethodPaperIsThePapersFilterBitForBit)
{
    Frame f;
    DenoiseImageOptions o = DenoiseImageOptions::paper();
    o.guides.albedo = o.guides.normal = GuideUse::Off;
    const OIIO::ImageBuf out = denoise(f.image, o);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    expect_rgb_equals(
        out, test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, DenoiseOptions::paper()));
}

TEST(DenoiseOperator, AnOlderFilesPositionLayersAreKeptAndNotRead)
{
    Frame f;
    const OIIO::ImageBuf older = test::with_retired_position_layers(f.image);
    const OIIO::ImageBuf out = denoise(older, DenoiseImageOptions{});
    ASSERT_FALSE(out.has_error()) << out.geterror();
    const OIIO::ImageBuf current = denoise(f.image, DenoiseImageOptions{});
    ASSERT_FALSE(current.has_error()) << current.geterror();
    for (const char* channel : {"R", "G", "B"})
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_TRUE(same_bits(channel_value(out, channel, x, y),
                                      channel_value(current, channel, x, y)))
                    << channel << " at (" << x << ", " << y << ")";
    EXPECT_EQ(out.spec().nchannels, older.spec().nchannels);
    EXPECT_EQ(channel_value(out, "subpixel.UU", 3, 2), -0.25f);
}

TEST(DenoiseOperator, RoiAtTheCornerAndDataWindowOffset)
{
    Frame f;
    OIIO::ImageBuf shifted = f.image;
    shifted.set_origin(-7, 30);
    const auto full = test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter());
    expect_rgb_equals(denoise(shifted, options()), full);
    // A ROI hanging over the data window's corner is clipped to it.
    const OIIO::ImageBuf out = denoise(shifted, options(), OIIO::ROI(-20, -3, 20, 34));
    ASSERT_FALSE(out.has_error()) << out.geterror();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool inside = x < 4 && y < 4;
            const float want =
                inside ? full[std::size_t(y) * kW + x] : channel_value(f.image, "R", x, y);
            ASSERT_TRUE(same_bits(channel_value(out, "R", x - 7, y + 30), want))
                << "(" << x << ", " << y << ")";
        }
    EXPECT_EQ(denoise(shifted, options(), OIIO::ROI(0, 5, 0, 5)).geterror(),
              "the ROI does not overlap the data window");
}

TEST(DenoiseOperator, APixelMaskComputesItsPixelsAloneAndKeepsTheRest)
{
    // The default method (ladder, context test, guides) on a shifted data window: the
    // pixels the mask wants inside the ROI come out as the full denoise's, bit for bit;
    // every other pixel keeps its input. In place too.
    Frame f;
    OIIO::ImageBuf shifted = f.image;
    shifted.set_origin(-7, 30);
    DenoiseImageOptions o;
    o.guides.albedo = o.guides.normal = GuideUse::Required;
    const OIIO::ImageBuf full = denoise(shifted, o);
    ASSERT_FALSE(full.has_error()) << full.geterror();
    PixelMask where(std::size_t(kW) * kH, 0);
    for (std::size_t i = 0; i < where.size(); i += 7)
        where[i] = 1;
    where.front() = where.back() = 1;
    const OIIO::ROI roi(-7, -7 + kW - 3, 31, 30 + kH);  // all but a column strip and row 0
    OIIO::ImageBuf in_place = shifted;
    ASSERT_TRUE(denoise(in_place, in_place, where, o, roi)) << in_place.geterror();
    OIIO::ImageBuf copy;
    ASSERT_TRUE(denoise(copy, shifted, where, o, roi)) << copy.geterror();
    for (const OIIO::ImageBuf* out : {&in_place, &copy}) {
        int computed = 0, moved = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const bool wanted = where[std::size_t(y) * kW + x] && roi.contains(x - 7, y + 30);
                computed += wanted;
                moved += wanted && channel_value(full, "R", x - 7, y + 30) !=
                                       channel_value(shifted, "R", x - 7, y + 30);
                const OIIO::ImageBuf& expected = wanted ? full : shifted;
                for (const char* c : {"R", "G", "B"})
                    ASSERT_TRUE(same_bits(channel_value(*out, c, x - 7, y + 30),
                                          channel_value(expected, c, x - 7, y + 30)))
                        << c << " at (" << x << ", " << y << ") wanted=" << wanted;
            }
        EXPECT_GT(computed, kW * kH / 8);
        EXPECT_GT(moved, computed / 2);  // the pixels compared were denoised
    }
    OIIO::ImageBuf out;
    EXPECT_FALSE(denoise(out, shifted, PixelMask(5, 1), o));
    EXPECT_NE(out.geterror().find("the pixel mask has 5 entries"), std::string::npos)
        << out.geterror();
}

TEST(DenoiseOperator, EveryOtherChannelAndAttributeIsKept)
{
    Frame f;
    OIIO::ImageBuf src = f.image;
    src.specmod().attribute("statmc:spp", 8);
    src.specmod().attribute("renderer:name", "test");
    const float camera[16] = {1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 3, 0, 4, 5, 6, 1};
    src.specmod().attribute("worldtocamera", OIIO::TypeMatrix, camera);
    OIIO::ImageBuf out;
    ASSERT_TRUE(denoise(out, src, options(GuideUse::Required))) << out.geterror();
    ASSERT_EQ(out.spec().channelnames, src.spec().channelnames);
    for (int c = 0; c < src.spec().nchannels; ++c) {
        const std::string& name = src.spec().channelnames[c];
        if (name == "R" || name == "G" || name == "B")
            continue;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_TRUE(same_bits(out.getchannel(x, y, 0, c), src.getchannel(x, y, 0, c)))
                    << name << " at (" << x << ", " << y << ")";
    }
    for (const OIIO::ParamValue& p : src.spec().extra_attribs) {
        const OIIO::ParamValue* q = out.spec().find_attribute(p.name());
        ASSERT_TRUE(q) << p.name();
        EXPECT_EQ(q->get_string(), p.get_string()) << p.name();
    }
    EXPECT_EQ(out.spec().get_int_attribute("statmc:denoised"), 1);
}

TEST(DenoiseOperator, DstMayBeSrcAndThreadCountDoesNotMatter)
{
    Frame f;
    const OIIO::ImageBuf once = denoise(f.image, options(), {}, 1);
    OIIO::ImageBuf in_place = f.image;
    ASSERT_TRUE(denoise(in_place, in_place, options(), {}, 0)) << in_place.geterror();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            ASSERT_TRUE(
                same_bits(channel_value(in_place, "B", x, y), channel_value(once, "B", x, y)));
}

// Every channel's pixels bit for bit, the channel names and every header attribute.
void expect_identical_images(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b)
{
    ASSERT_EQ(a.spec().channelnames, b.spec().channelnames);
    ASSERT_EQ(a.roi(), b.roi());
    EXPECT_EQ(a.spec().serialize(OIIO::ImageSpec::SerialText),
              b.spec().serialize(OIIO::ImageSpec::SerialText));
    std::vector<float> pa(a.spec().image_pixels() * a.nchannels()), pb(pa.size());
    ASSERT_TRUE(a.get_pixels(a.roi(), OIIO::TypeDesc::FLOAT, pa.data()));
    ASSERT_TRUE(b.get_pixels(b.roi(), OIIO::TypeDesc::FLOAT, pb.data()));
    EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0);
}

TEST(DenoiseOperator, InPlaceGivesTheCopysImageForEveryInputForm)
{
    // In place the means are patched into the input's float pixels (or its float
    // conversion) instead of a copy; nothing else may differ.
    Frame f;
    f.image.set_origin(3, -2);
    const OIIO::ROI corner(3, 20, -2, 9);
    DenoiseImageOptions with_diagnostics = options();
    with_diagnostics.diagnostics = true;
    struct Form {
        const char* what;
        OIIO::TypeDesc type;
        OIIO::ROI roi;
        DenoiseImageOptions opt;
    };
    for (const Form& form :
         {Form{"float", OIIO::TypeDesc::FLOAT, {}, options()},
          Form{"half", OIIO::TypeDesc::HALF, {}, options()},
          Form{"float, ROI", OIIO::TypeDesc::FLOAT, corner, options()},
          Form{"float, diagnostics", OIIO::TypeDesc::FLOAT, {}, with_diagnostics}}) {
        SCOPED_TRACE(form.what);
        const OIIO::ImageBuf input = f.image.copy(form.type);
        const OIIO::ImageBuf copied = denoise(input, form.opt, form.roi);
        ASSERT_FALSE(copied.has_error()) << copied.geterror();
        OIIO::ImageBuf in_place = input.copy(form.type);
        ASSERT_TRUE(denoise(in_place, in_place, form.opt, form.roi)) << in_place.geterror();
        expect_identical_images(in_place, copied);
        EXPECT_GT(changed_pixels(in_place, f.image.copy(OIIO::TypeDesc::FLOAT)), 0u);
    }
}

TEST(DenoiseOperator, NonFiniteStatisticsAreRefusedOrZeroed)
{
    Frame f;
    OIIO::ImageBuf bad = f.image;
    test::set_channel(bad, "G", 6, 2, std::numeric_limits<float>::quiet_NaN());
    OIIO::ImageBuf out;
    EXPECT_FALSE(denoise(out, bad, options()));
    EXPECT_EQ(out.geterror(), "G: NaN at pixel (6, 2) [1 pixel affected]");

    DenoiseImageOptions zero = options();
    zero.nonfinite = NonfinitePolicy::Zero;
    ASSERT_TRUE(denoise(out, bad, zero)) << out.geterror();
    const StatisticsView view = layers::read_statistics(bad);
    const auto expected = test::core_filtered(view, TestDomain::BoxCox, {}, small_filter());
    expect_rgb_equals(out, expected);
    EXPECT_EQ(channel_value(out, "G", 6, 2), 0.f);  // the pixel keeps core's stand-in
}

TEST(DenoiseOperator, BadStatisticsAreRefusedEvenWhenZeroingNonFinite)
{
    Frame f;
    DenoiseImageOptions zero = options();
    zero.nonfinite = NonfinitePolicy::Zero;
    OIIO::ImageBuf count0 = f.image;
    test::set_channel(count0, "sampleCount.Y", 3, 4, 0.f);
    OIIO::ImageBuf out;
    EXPECT_FALSE(denoise(out, count0, zero));
    EXPECT_EQ(out.geterror(), "sampleCount.Y: n = 0 at pixel (3, 4) [1 pixel affected]");

    OIIO::ImageBuf negative = f.image;
    test::set_channel(negative, "boxcoxVariance.G", 12, 7, -0.3f);
    EXPECT_FALSE(denoise(out, negative, zero));
    EXPECT_EQ(out.geterror(),
              "boxcoxVariance.G: negative value -0.3 at pixel (12, 7) [1 pixel affected]");
    // Only the planes the chosen test reads are checked: the raw variance is unused here.
    OIIO::ImageBuf unused = f.image;
    test::set_channel(unused, "variance.G", 12, 7, -0.3f);
    EXPECT_TRUE(denoise(out, unused, options())) << out.geterror();
}

TEST(DenoiseOperator, MissingStatisticsAndBadOptionsAreErrorsNotExceptions)
{
    Frame f;
    OIIO::ImageBuf out;
    const OIIO::ImageBuf no_variance = test::without_channels(
        f.image, {"variance.R", "variance.G", "variance.B", "boxcoxMean.R", "boxcoxMean.G",
                  "boxcoxMean.B", "boxcoxVariance.R", "boxcoxVariance.G", "boxcoxVariance.B",
                  "boxcoxM3.R", "boxcoxM3.G", "boxcoxM3.B"});
    EXPECT_FALSE(denoise(out, no_variance, options()));
    EXPECT_EQ(out.geterror().rfind(
                  "missing layer variance (channels variance.R, variance.G, variance.B)", 0),
              0u);

    DenoiseImageOptions boxcox = options();
    boxcox.test = TestDomainChoice::BoxCox;
    const OIIO::ImageBuf plain =
        test::without_channels(f.image, {"boxcoxMean.R", "boxcoxMean.G", "boxcoxMean.B",
                                         "boxcoxVariance.R", "boxcoxVariance.G", "boxcoxVariance.B",
                                         "boxcoxM3.R", "boxcoxM3.G", "boxcoxM3.B"});
    EXPECT_FALSE(denoise(out, plain, boxcox));
    EXPECT_EQ(out.geterror().rfind("missing layer boxcoxMean", 0), 0u);

    DenoiseImageOptions bad = options();
    bad.filter.radius = -3;
    EXPECT_FALSE(denoise(out, f.image, bad));
    EXPECT_EQ(out.geterror(), "radius must be in [0, 1000], got -3");

    EXPECT_FALSE(denoise(out, OIIO::ImageBuf(), options()));
    EXPECT_EQ(out.geterror(), "uninitialized input image");
}

TEST(DenoiseOperator, AnAovIsDenoisedUnderItsPrefix)
{
    Frame f;
    layers::StatisticsMetadata meta;
    meta.aov = "diffuse";
    const OIIO::ImageBuf image = layers::make_statistics_image(f.stats, meta);
    DenoiseImageOptions opt = options();
    opt.aov = "diffuse";
    const OIIO::ImageBuf out = denoise(image, opt);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    const auto expected =
        test::core_filtered(f.stats.view(), TestDomain::BoxCox, {}, small_filter());
    const std::size_t n = std::size_t(kW) * kH;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_TRUE(same_bits(channel_value(out, std::string("diffuse.") + "RGB"[c], x, y),
                                      expected[c * n + std::size_t(y) * kW + x]));
    EXPECT_FALSE(denoise(image, options()).geterror().empty());  // no beauty R,G,B
}

TEST(DenoiseOperator, OneChannelQuantityUsesY)
{
    StatisticsImage<1> acc(kW, kH);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int s = 0; s < 6; ++s) {
                const float v = (x < kW / 2 ? 0.1f : 0.6f) * 2.f * u(rng);
                acc.add(x, y, &v);
            }
    const StatisticsPlanes stats = acc.planes();
    const OIIO::ImageBuf image = layers::make_statistics_image(stats);
    EXPECT_EQ(image.spec().channelnames.front(), "Y");
    const OIIO::ImageBuf out = denoise(image, options());
    ASSERT_FALSE(out.has_error()) << out.geterror();
    const auto expected = test::core_filtered(stats.view(), TestDomain::BoxCox, {}, small_filter());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            ASSERT_TRUE(
                same_bits(channel_value(out, "Y", x, y), expected[std::size_t(y) * kW + x]));
}

TEST(DenoiseOperator, HalfInputIsDenoisedAsItsFloatConversion)
{
    Frame f;
    const OIIO::ImageBuf half = f.image.copy(OIIO::TypeDesc::HALF);
    const OIIO::ImageBuf as_float = half.copy(OIIO::TypeDesc::FLOAT);
    const OIIO::ImageBuf a = denoise(half, options());
    const OIIO::ImageBuf b = denoise(as_float, options());
    ASSERT_FALSE(a.has_error()) << a.geterror();
    EXPECT_EQ(a.spec().format, OIIO::TypeDesc::FLOAT);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            ASSERT_TRUE(same_bits(channel_value(a, "R", x, y), channel_value(b, "R", x, y)));
}

}  // namespace
}  // namespace statmc
