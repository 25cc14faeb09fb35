// The compare operator against numbers worked out independently: zero error for identical
// images, a constant offset, relMSE by hand, SSIM of flat images in closed form, and SSIM
// falling as noise grows.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/compare/compare.h"

namespace statmc {
namespace {

OIIO::ImageBuf rgb_image(int w, int h, const std::vector<float>& pixels)
{
    OIIO::ImageBuf buf(OIIO::ImageSpec(w, h, 3, OIIO::TypeFloat));
    buf.set_pixels(buf.roi(), OIIO::TypeFloat, pixels.data());
    return buf;
}

OIIO::ImageBuf flat(int w, int h, float value)
{
    return rgb_image(w, h, std::vector<float>(std::size_t(w) * h * 3, value));
}

// A textured reference in (0, 1): gradients plus a checker, so SSIM has structure to see.
std::vector<float> textured(int w, int h)
{
    std::vector<float> p;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                p.push_back(0.05f + 0.4f * x / w + 0.2f * y / h + 0.1f * c +
                            (((x / 4) + (y / 4)) % 2 ? 0.1f : 0.f));
    return p;
}

CompareMetrics metrics(const OIIO::ImageBuf& x, const OIIO::ImageBuf& ref,
                       OIIO::ImageBuf* error_out = nullptr)
{
    CompareMetrics m;
    OIIO::ImageBuf error;
    EXPECT_TRUE(compare(m, error, x, ref)) << error.geterror();
    if (error_out)
        *error_out = error;
    return m;
}

TEST(Compare, IdenticalImagesHaveNoError)
{
    const OIIO::ImageBuf ref = rgb_image(16, 12, textured(16, 12));
    const CompareMetrics m = metrics(ref, ref);
    EXPECT_EQ(m.rmse, 0);
    EXPECT_EQ(m.mae, 0);
    EXPECT_EQ(m.relmse, 0);
    EXPECT_NEAR(m.ssim, 1, 1e-12);
    EXPECT_NEAR(m.dssim, 0, 1e-12);
}

TEST(Compare, ConstantOffsetIsTheRmseAndMae)
{
    const std::vector<float> ref = textured(16, 12);
    std::vector<float> x = ref;
    for (float& v : x)
        v += 0.125f;  // exact in float, so the differences are exactly δ
    OIIO::ImageBuf error;
    const CompareMetrics m = metrics(rgb_image(16, 12, x), rgb_image(16, 12, ref), &error);
    EXPECT_NEAR(m.rmse, 0.125, 1e-6);
    EXPECT_NEAR(m.mae, 0.125, 1e-6);
    EXPECT_NEAR(error.getchannel(5, 7, 0, 2), 0.125f, 1e-6f);
}

TEST(Compare, RelMseByHand)
{
    const std::vector<float> ref = {1.f, 0.f, 0.5f, 2.f, 0.25f, 0.f};
    const std::vector<float> x = {1.5f, 0.125f, 0.5f, 1.f, 0.25f, 0.25f};
    // Σ (x − r)² / (r² + 0.01) over the six values, divided by 6.
    const double want = (0.25 / 1.01 + 0.015625 / 0.01 + 0 + 1 / 4.01 + 0 + 0.0625 / 0.01) / 6;
    EXPECT_NEAR(metrics(rgb_image(2, 1, x), rgb_image(2, 1, ref)).relmse, want, 1e-9);
}

TEST(Compare, SsimOfFlatImagesIsTheLuminanceTerm)
{
    // 0.18 encodes to 0.461356 in sRGB, 1 to 1; flat images have no variance, so SSIM is
    // (2·a·b + C1) / (a² + b² + C1) with C1 = 0.01².
    const double a = 0.461356, b = 1, c1 = 1e-4;
    const CompareMetrics m = metrics(flat(13, 13, 0.18f), flat(13, 13, 1.f));
    EXPECT_NEAR(m.ssim, (2 * a * b + c1) / (a * a + b * b + c1), 1e-5);
    EXPECT_NEAR(m.dssim, (1 - m.ssim) / 2, 1e-12);
}

TEST(Compare, SsimFallsAsNoiseGrows)
{
    const int w = 48, h = 40;
    const std::vector<float> ref = textured(w, h);
    double previous = 1;
    for (const float sigma : {0.005f, 0.02f, 0.05f, 0.1f, 0.3f}) {
        std::mt19937 rng(3);
        std::normal_distribution<float> noise(0.f, sigma);
        std::vector<float> x = ref;
        for (float& v : x)
            v += noise(rng);
        const double ssim = metrics(rgb_image(w, h, x), rgb_image(w, h, ref)).ssim;
        EXPECT_LT(ssim, previous) << "sigma " << sigma;
        previous = ssim;
    }
    EXPECT_LT(previous, 0.5);
}

TEST(Compare, SsimSeesTheImagesThroughTheDisplayView)
{
    const int w = 32, h = 24;
    const std::vector<float> ref = textured(w, h);
    std::vector<float> x = ref;
    std::mt19937 rng(5);
    std::normal_distribution<float> noise(0.f, 0.05f);
    for (float& v : x)
        v += noise(rng);
    CompareOptions options;
    const double plain = metrics(rgb_image(w, h, x), rgb_image(w, h, ref)).ssim;
    CompareMetrics m;
    OIIO::ImageBuf error;
    // statmc's sRGB view is the sRGB encoding, so SSIM is the same through it.
    options.display = DisplayOptions{STATMC_DISPLAY_CONFIG, "sRGB", "sRGB"};
    ASSERT_TRUE(compare(m, error, rgb_image(w, h, x), rgb_image(w, h, ref), options))
        << error.geterror();
    EXPECT_NEAR(m.ssim, plain, 1e-5);
    options.display->view = "Filmic";
    ASSERT_TRUE(compare(m, error, rgb_image(w, h, x), rgb_image(w, h, ref), options));
    EXPECT_GT(std::abs(m.ssim - plain), 1e-3);
    options.display->view = "Nope";
    EXPECT_FALSE(compare(m, error, rgb_image(w, h, x), rgb_image(w, h, ref), options));
    EXPECT_NE(error.geterror().find("view 'Nope' of display 'sRGB'"), std::string::npos);
}

TEST(Compare, RefusesDifferentWindowsAndMissingChannels)
{
    CompareMetrics m;
    OIIO::ImageBuf error;
    EXPECT_FALSE(compare(m, error, flat(4, 4, 0.5f), flat(5, 4, 0.5f)));
    EXPECT_NE(error.geterror().find("the image and the reference differ in resolution: 4x4 vs 5x4"),
              std::string::npos)
        << error.geterror();
    OIIO::ImageBuf moved = flat(4, 4, 0.5f);
    moved.set_origin(1, 0);
    EXPECT_FALSE(compare(m, error, flat(4, 4, 0.5f), moved));
    EXPECT_NE(error.geterror().find("differ in data window: origin (0, 0) vs (1, 0)"),
              std::string::npos)
        << error.geterror();
    OIIO::ImageBuf gray(OIIO::ImageSpec(4, 4, 1, OIIO::TypeFloat));
    OIIO::ImageBuf error2;
    EXPECT_FALSE(compare(m, error2, flat(4, 4, 0.5f), gray));
    const std::string message = error2.geterror();
    EXPECT_NE(message.find("the reference has no channel"), std::string::npos) << message;
}

// `rgb` as Blender writes a multilayer reference: ViewLayer.Combined.R,G,B,A.
OIIO::ImageBuf as_cycles_multilayer(const OIIO::ImageBuf& rgb)
{
    return OIIO::ImageBufAlgo::channels(
        rgb, 4, {0, 1, 2, -1}, {0.f, 0.f, 0.f, 1.f},
        {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
         "ViewLayer.Combined.A"});
}

TEST(Compare, ReadsAnotherRenderersBeautyByItsPreset)
{
    const std::vector<float> ref = textured(16, 12);
    std::vector<float> x = ref;
    for (float& v : x)
        v += 0.125f;
    const OIIO::ImageBuf cycles_ref = as_cycles_multilayer(rgb_image(16, 12, ref));
    ASSERT_EQ(cycles_ref.spec().channelindex("R"), -1);
    const CompareMetrics m = metrics(rgb_image(16, 12, x), cycles_ref);
    EXPECT_NEAR(m.rmse, 0.125, 1e-6);
    EXPECT_EQ(metrics(cycles_ref, cycles_ref).rmse, 0);
}

}  // namespace
}  // namespace statmc
