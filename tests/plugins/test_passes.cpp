// K renders with values chosen so that mean and variance are exact in float: the
// operator's statistics must equal the hand-computed ones bit for bit.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/core/passes.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/passes/passes.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc {
namespace {

using test::channel_value;

constexpr int kW = 11, kH = 7, kK = 3;

// Render k of pixel (x, y), channel c: base + k·step, so over k = 0, 1, 2 the mean is
// base + step and the sample variance ((−step)² + 0 + step²)/2 = step², all exact.
float base(int x, int y, int c) { return 0.5f * float(x + y * kW) + float(c); }
float step(int x, int c) { return 0.25f * float(1 + (x + c) % 3); }

OIIO::ImageBuf render(int k, bool with_albedo = true)
{
    OIIO::ImageSpec spec(kW, kH, with_albedo ? 7 : 4, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B", "A"};
    if (with_albedo)
        spec.channelnames.insert(spec.channelnames.end(), {"albedo.R", "albedo.G", "albedo.B"});
    spec.alpha_channel = 3;
    spec.attribute("renderer:seed", k);
    spec.attribute("statmc:spp", 4);
    OIIO::ImageBuf img(spec);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            std::vector<float> px(spec.nchannels);
            for (int c = 0; c < 3; ++c)
                px[c] = base(x, y, c) + float(k) * step(x, c);
            px[3] = 1.f;
            for (int c = 4; c < spec.nchannels; ++c)
                px[c] = 0.25f * float(k + 1);  // mean over k = 0..2: 0.5
            img.setpixel(x, y, px.data());
        }
    return img;
}

std::vector<const OIIO::ImageBuf*> pointers(const std::vector<OIIO::ImageBuf>& images)
{
    std::vector<const OIIO::ImageBuf*> p;
    for (const auto& i : images)
        p.push_back(&i);
    return p;
}

TEST(PassesOperator, MeanVarianceAndCountAreTheHandComputedOnes)
{
    const std::vector<OIIO::ImageBuf> renders = {render(0), render(1), render(2)};
    OIIO::ImageBuf stats;
    ASSERT_TRUE(passes(stats, pointers(renders))) << stats.geterror();
    const char* colour[3] = {"R", "G", "B"};
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            EXPECT_EQ(channel_value(stats, "sampleCount.Y", x, y), float(kK));
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(channel_value(stats, colour[c], x, y), base(x, y, c) + step(x, c));
                EXPECT_EQ(channel_value(stats, std::string("variance.") + colour[c], x, y),
                          step(x, c) * step(x, c));
                // Deviations −step, 0, +step: M3/K = 0 and M4/K = 2·step⁴/3.
                const double s4 = std::pow(double(step(x, c)), 4);
                EXPECT_NEAR(channel_value(stats, std::string("M3.") + colour[c], x, y), 0.0,
                            1e-6 * (1 + s4));
                EXPECT_NEAR(channel_value(stats, std::string("M4.") + colour[c], x, y), 2 * s4 / 3,
                            1e-5 * (1 + s4));
            }
            EXPECT_EQ(channel_value(stats, "A", x, y), 1.f);
            EXPECT_EQ(channel_value(stats, "albedo.G", x, y), 0.5f);
            // Each render one sample: albedo 0.25, 0.5, 0.75 per channel, s² = 0.0625.
            EXPECT_EQ(channel_value(stats, "albedoVariance.Y", x, y), 3 * 0.0625f);
        }
    const OIIO::ImageSpec& spec = stats.spec();
    EXPECT_EQ(spec.get_string_attribute("statmc:variance"), "sample");
    EXPECT_EQ(spec.get_int_attribute("statmc:formatVersion"), 2);
    EXPECT_EQ(spec.get_int_attribute("renderer:seed", -1), 0);  // the first render's metadata
    EXPECT_FALSE(spec.find_attribute("statmc:spp"));            // described one render only
    EXPECT_EQ(spec.channelindex("boxcoxMean.R"), -1);
    EXPECT_EQ(spec.alpha_channel, spec.channelindex("A"));
}

TEST(PassesOperator, BrokenRenderPixelsCountAsZero)
{
    std::vector<OIIO::ImageBuf> renders = {render(0), render(1), render(2)};
    for (const char* c : {"R", "G", "B"})
        test::set_channel(renders[1], c, 2, 3, -1.f);  // negative luminance
    // One negative channel with positive luminance is a valid sample and is kept.
    test::set_channel(renders[1], "G", 5, 5, -2.f);
    test::set_channel(renders[2], "R", 4, 1, std::numeric_limits<float>::quiet_NaN());
    const OIIO::ImageBuf stats = passes(pointers(renders));
    ASSERT_FALSE(stats.has_error()) << stats.geterror();
    // Pixel (2, 3): samples r0, 0, r2 → mean (r0 + r2)/3, variance from the three values.
    for (int c = 0; c < 3; ++c) {
        const double r0 = base(2, 3, c), r2 = base(2, 3, c) + 2.0 * step(2, c);
        const double mean = (r0 + r2) / 3.0;
        const double var =
            ((r0 - mean) * (r0 - mean) + mean * mean + (r2 - mean) * (r2 - mean)) / 2.0;
        const std::string name = std::string(1, "RGB"[c]);
        EXPECT_FLOAT_EQ(channel_value(stats, name, 2, 3), float(mean)) << name;
        EXPECT_FLOAT_EQ(channel_value(stats, "variance." + name, 2, 3), float(var)) << name;
    }
    const double g0 = base(5, 5, 1), g2 = base(5, 5, 1) + 2.0 * step(5, 1);
    EXPECT_FLOAT_EQ(channel_value(stats, "G", 5, 5), float((g0 - 2.0 + g2) / 3.0));
    // Pixel (4, 1): render 2 counts as 0 in every channel.
    const double r0 = base(4, 1, 0), r1 = base(4, 1, 0) + step(4, 0);
    EXPECT_FLOAT_EQ(channel_value(stats, "R", 4, 1), float((r0 + r1) / 3.0));
}

TEST(PassesOperator, DenoisingThePassesTestsUntransformedWithTheirCount)
{
    std::vector<OIIO::ImageBuf> renders;
    for (int k = 0; k < 4; ++k) {
        renders.push_back(render(k % 3));
        // Noise that differs per render, so the test has something to decide.
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                test::set_channel(renders[k], "G", x, y,
                                  0.3f + 0.05f * float((x * 7 + y * 3 + k * 5) % 4));
    }
    const OIIO::ImageBuf stats = passes(pointers(renders));
    ASSERT_FALSE(stats.has_error()) << stats.geterror();
    DenoiseImageOptions opt;
    opt.guides.albedo = GuideUse::Off;  // the averaged albedo would steer the weights
    opt.filter.radius = 3;
    opt.filter.alpha = 0.05;
    const OIIO::ImageBuf out = denoise(stats, opt);
    ASSERT_FALSE(out.has_error()) << out.geterror();

    std::vector<std::vector<ConstPlane>> planes;
    for (const OIIO::ImageBuf& r : renders) {
        std::vector<ConstPlane> p;
        for (const char* name : {"R", "G", "B"})
            p.push_back(layers::channel_plane(r, r.spec().channelindex(name)));
        planes.push_back(p);
    }
    const StatisticsPlanes direct = statistics_from_passes(planes, kW, kH);
    const auto expected =
        test::core_filtered(direct.view(), TestDomain::Untransformed, {}, opt.filter);
    const std::size_t n = std::size_t(kW) * kH;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_TRUE(test::same_bits(channel_value(out, std::string(1, "RGB"[c]), x, y),
                                            expected[c * n + std::size_t(y) * kW + x]));
}

TEST(PassesOperator, RoiSelectsTheRegionAndKeepsItsCoordinates)
{
    const std::vector<OIIO::ImageBuf> renders = {render(0), render(1), render(2)};
    const OIIO::ImageBuf stats = passes(pointers(renders), OIIO::ROI(3, 8, 2, 5));
    ASSERT_FALSE(stats.has_error()) << stats.geterror();
    EXPECT_EQ(stats.spec().x, 3);
    EXPECT_EQ(stats.spec().y, 2);
    EXPECT_EQ(stats.spec().width, 5);
    EXPECT_EQ(stats.spec().height, 3);
    EXPECT_EQ(channel_value(stats, "B", 7, 4), base(7, 4, 2) + step(7, 2));
}

std::string passes_error(const std::vector<OIIO::ImageBuf>& renders)
{
    OIIO::ImageBuf out;
    EXPECT_FALSE(passes(out, pointers(renders)));
    return out.geterror();
}

TEST(PassesOperator, MismatchedRendersAreRefusedNamingBoth)
{
    std::vector<OIIO::ImageBuf> renders = {render(0), render(1), render(2)};
    OIIO::ImageBuf smaller(OIIO::ImageSpec(kW, kH - 1, 7, OIIO::TypeDesc::FLOAT));
    smaller.specmod().channelnames = renders[0].spec().channelnames;
    EXPECT_EQ(passes_error({renders[0], renders[1], smaller}),
              "render 2 and render 0 differ in resolution: 11x6 vs 11x7");

    OIIO::ImageBuf moved = renders[2];
    moved.set_origin(1, 0);
    EXPECT_EQ(passes_error({renders[0], moved}),
              "render 1 and render 0 differ in data window: origin (1, 0) vs (0, 0)");

    EXPECT_EQ(passes_error({renders[0], render(1, false)}),
              "render 1 and render 0 differ in channels: only in render 1: none; only in "
              "render 0: albedo.R, albedo.G, albedo.B");

    EXPECT_EQ(passes_error({renders[0]}), "passes needs at least 2 renders, got 1");
}

TEST(PassesOperator, RendersOfOtherSampleCountsAreRefused)
{
    // Blender Cycles writes the samples per pixel into the header as a string.
    std::vector<OIIO::ImageBuf> renders = {render(0), render(1), render(2)};
    renders[0].specmod().attribute("cycles.ViewLayer.samples", "8");
    renders[1].specmod().attribute("cycles.ViewLayer.samples", "8");
    renders[2].specmod().attribute("cycles.ViewLayer.samples", "16384");
    EXPECT_EQ(passes_error(renders),
              "render 2 declares 16384 samples per pixel (cycles.ViewLayer.samples) and render 0 "
              "8: passes takes renders of one sample count (each is one sample of the pixel's "
              "estimator)");
    renders[2].specmod().attribute("cycles.ViewLayer.samples", "8");
    EXPECT_FALSE(passes(pointers(renders)).has_error());
    // A render that declares nothing is not compared.
    renders[2].specmod().erase_attribute("cycles.ViewLayer.samples");
    EXPECT_FALSE(passes(pointers(renders)).has_error());
}

TEST(PassesOperator, StatisticsImagesAreNotRenders)
{
    const std::vector<OIIO::ImageBuf> renders = {render(0), render(1), render(2)};
    const OIIO::ImageBuf stats = passes(pointers(renders));
    EXPECT_EQ(passes_error({stats, stats}).rfind("render 0 already holds statistics (", 0), 0u);
}

TEST(PassesOperator, ImagesAreNamedByTheirFile)
{
    test::TempDir dir;
    test::write_exr(render(0), dir.file("a.exr"));
    test::write_exr(render(1, false), dir.file("b.exr"));
    const std::vector<OIIO::ImageBuf> renders = {test::read_exr(dir.file("a.exr")),
                                                 test::read_exr(dir.file("b.exr"))};
    const std::string error = passes_error(renders);
    EXPECT_EQ(error.rfind("render 1 (" + dir.file("b.exr") + ") and render 0 (" +
                              dir.file("a.exr") + ") differ in channels",
                          0),
              0u)
        << error;
}

// render(k) as Blender writes a multilayer EXR: every channel under the view layer, the
// beauty as `beauty` (Combined, or Noisy Image when Blender denoised Combined).
OIIO::ImageBuf blender_multilayer(int k, const std::string& beauty, bool denoised_combined)
{
    const OIIO::ImageBuf plain = render(k);
    std::vector<int> order;
    std::vector<float> values;
    std::vector<std::string> names;
    for (int c = 0; c < plain.nchannels(); ++c) {
        const std::string& name = plain.spec().channelnames[c];
        order.push_back(c);
        values.push_back(0.f);
        names.push_back(c < 4 ? "ViewLayer." + beauty + "." + name
                              : "ViewLayer.Denoising Albedo." + name.substr(name.size() - 1));
    }
    if (denoised_combined)
        for (const char* c : {"R", "G", "B", "A"}) {
            order.push_back(-1);
            values.push_back(0.5f);
            names.push_back(std::string("ViewLayer.Combined.") + c);
        }
    OIIO::ImageBuf out =
        OIIO::ImageBufAlgo::channels(plain, int(order.size()), order, values, names);
    out.specmod().attribute("cycles.ViewLayer.samples", "8");
    return out;
}

TEST(PassesOperator, BlenderMultilayerRendersAreReadUnderTheContractsNames)
{
    const std::vector<OIIO::ImageBuf> plain = {render(0), render(1), render(2)};
    const OIIO::ImageBuf expected = passes(pointers(plain));
    for (const bool noisy : {false, true}) {
        const std::string beauty = noisy ? "Noisy Image" : "Combined";
        const std::vector<OIIO::ImageBuf> blender = {blender_multilayer(0, beauty, noisy),
                                                     blender_multilayer(1, beauty, noisy),
                                                     blender_multilayer(2, beauty, noisy)};
        const OIIO::ImageBuf got = passes(pointers(blender));
        ASSERT_FALSE(got.has_error()) << got.geterror();
        for (const char* name : {"R", "G", "B", "A", "variance.R", "variance.B", "sampleCount.Y",
                                 "albedo.R", "albedo.B"})
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    ASSERT_TRUE(test::same_bits(channel_value(got, name, x, y),
                                                channel_value(expected, name, x, y)))
                        << beauty << " " << name << " at (" << x << ", " << y << ")";
        // Blender's own denoised Combined is carried, never taken as the beauty.
        EXPECT_EQ(got.spec().channelindex("ViewLayer.Combined.R") >= 0, noisy);
    }
    // Named explicitly as something else, the beauty is missing and said so.
    const std::vector<OIIO::ImageBuf> blender = {blender_multilayer(0, "Combined", false),
                                                 blender_multilayer(1, "Combined", false)};
    OIIO::ImageBuf out;
    PassesOptions pbrt;
    pbrt.from = "pbrt-v4";
    EXPECT_FALSE(passes(out, pointers(blender), pbrt));
    EXPECT_NE(out.geterror().find("from=pbrt-v4) needs channels R, G, B"), std::string::npos)
        << out.geterror();
}

TEST(PassesOperator, BlenderFilesOfOneSeedAreRefusedNamingBoth)
{
    // Blender's defaults (seed 0, animated seed off) render a frame identically every time.
    test::TempDir dir;
    const std::string a = dir.file("noseed1-0001.exr"), b = dir.file("noseed2-0001.exr"),
                      c = dir.file("seed2-0001.exr");
    test::write_exr(blender_multilayer(0, "Combined", false), a);
    test::write_exr(blender_multilayer(0, "Combined", false), b);
    test::write_exr(blender_multilayer(1, "Combined", false), c);
    const std::vector<OIIO::ImageBuf> same = {test::read_exr(a), test::read_exr(b)};
    const std::string error = passes_error(same);
    EXPECT_EQ(error.rfind("render 1 (" + b + ") and render 0 (" + a +
                              ") hold the same pixels: they were rendered with one seed",
                          0),
              0u)
        << error;
    EXPECT_NE(error.find("scene.cycles.seed"), std::string::npos) << error;
    // One distinct render does not make the pair distinct.
    EXPECT_NE(passes_error({test::read_exr(c), test::read_exr(a), test::read_exr(b)})
                  .find("render 2 (" + b + ") and render 1 (" + a + ") hold the same pixels"),
              std::string::npos);
    // Renders that differ in a single pixel are distinct renders.
    OIIO::ImageBuf one_pixel = blender_multilayer(0, "Combined", false);
    float px[8];
    one_pixel.getpixel(3, 2, px, 8);
    px[1] += 0.125f;
    one_pixel.setpixel(3, 2, px, 8);
    EXPECT_FALSE(passes(pointers({test::read_exr(a), one_pixel})).has_error());
}

TEST(PassesOperator, BlenderLightGroupsBecomeAovsThatDenoiseJointly)
{
    // Two light groups that sum to Combined, as Cycles writes them (Combined_<group>).
    std::vector<OIIO::ImageBuf> renders;
    for (int k = 0; k < 4; ++k) {
        OIIO::ImageBuf r = blender_multilayer(k, "Combined", false);
        OIIO::ImageSpec spec = r.spec();
        std::vector<int> order;
        std::vector<std::string> names = spec.channelnames;
        for (int c = 0; c < spec.nchannels; ++c)
            order.push_back(c);
        for (const char* group : {"key", "fill"})
            for (const char* c : {"R", "G", "B"}) {
                order.push_back(-1);
                names.push_back(std::string("ViewLayer.Combined_") + group + "." + c);
            }
        std::vector<float> zeros(order.size(), 0.f);
        r = OIIO::ImageBufAlgo::channels(r, int(order.size()), order, zeros, names);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (const char* c : {"R", "G", "B"}) {
                    const float all =
                        channel_value(r, std::string("ViewLayer.Combined.") + c, x, y);
                    const float key = 0.75f * all + 0.01f * float((x + 3 * y + k) % 5);
                    test::set_channel(r, std::string("ViewLayer.Combined_key.") + c, x, y, key);
                    test::set_channel(r, std::string("ViewLayer.Combined_fill.") + c, x, y,
                                      all - key);
                }
        renders.push_back(r);
    }
    const OIIO::ImageBuf stats = passes(pointers(renders));
    ASSERT_FALSE(stats.has_error()) << stats.geterror();
    // The groups are AOVs now, each the mean of its renders.
    EXPECT_FLOAT_EQ(channel_value(stats, "key.G", 4, 3),
                    0.25f * (channel_value(renders[0], "ViewLayer.Combined_key.G", 4, 3) +
                             channel_value(renders[1], "ViewLayer.Combined_key.G", 4, 3) +
                             channel_value(renders[2], "ViewLayer.Combined_key.G", 4, 3) +
                             channel_value(renders[3], "ViewLayer.Combined_key.G", 4, 3)));
    EXPECT_EQ(stats.spec().channelindex("ViewLayer.Combined_key.G"), -1);
    DenoiseImageOptions opt;
    opt.filter.radius = 3;
    opt.aovs = {"key", "fill"};
    opt.joint = true;
    const OIIO::ImageBuf out = denoise(stats, opt);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double sum =
                double(channel_value(out, "key.R", x, y)) + channel_value(out, "fill.R", x, y);
            EXPECT_NEAR(sum, channel_value(out, "R", x, y), 1e-5 * std::abs(sum) + 1e-6);
        }
}

}  // namespace
}  // namespace statmc
