// The display operator with the config statmc ships: the sRGB view against the sRGB
// formula, the filmic view against its log curve, and errors naming display and view.
#include <cmath>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/display/display.h"

namespace statmc {
namespace {

const std::string kConfig = STATMC_DISPLAY_CONFIG;

OIIO::ImageBuf gray_rgba(float value, float alpha = 0.5f)
{
    OIIO::ImageBuf buf(OIIO::ImageSpec(3, 2, 4, OIIO::TypeFloat));
    const float px[4] = {value, value, value, alpha};
    OIIO::ImageBufAlgo::fill(buf, px);
    return buf;
}

float shown(float linear, const std::string& view, int channel = 0)
{
    const OIIO::ImageBuf out = display(gray_rgba(linear), {kConfig, "sRGB", view});
    EXPECT_FALSE(out.has_error()) << out.geterror();
    return out.getchannel(2, 1, 0, channel);
}

TEST(Display, SrgbViewIsTheSrgbEncoding)
{
    EXPECT_NEAR(shown(0.18f, "sRGB"), 0.461356f, 1e-4f);         // docs/ecosystem.md §4
    EXPECT_NEAR(shown(0.002f, "sRGB"), 12.92f * 0.002f, 1e-5f);  // the linear toe
    EXPECT_NEAR(shown(0.18f, "sRGB", 3), 0.5f, 0.f);             // alpha untouched
    // The defaults are the config's display and view: sRGB / sRGB.
    const OIIO::ImageBuf out = display(gray_rgba(0.18f), {kConfig, "", ""});
    EXPECT_NEAR(out.getchannel(0, 0, 0, 1), 0.461356f, 1e-4f);
}

TEST(Display, FilmicViewIsALogCurveWithAShoulder)
{
    const auto curve = [](double x) { return std::log2(x + 0.0039) * 0.0606061 + 0.6; };
    EXPECT_NEAR(shown(0.18f, "Filmic"), curve(0.18), 1e-4);
    EXPECT_NEAR(shown(4.f, "Filmic"), curve(4), 1e-4);
    EXPECT_EQ(shown(1000.f, "Filmic"), 1.f);
    float previous = -1;
    for (float x : {0.f, 0.01f, 0.1f, 0.5f, 1.f, 10.f}) {
        EXPECT_GT(shown(x, "Filmic"), previous) << x;
        previous = shown(x, "Filmic");
    }
}

TEST(Display, ReadsAnotherRenderersBeautyByItsPreset)
{
    // Blender's multilayer names: ViewLayer.Combined.R,G,B,A.
    const OIIO::ImageBuf cycles = OIIO::ImageBufAlgo::channels(
        gray_rgba(0.18f), 4, {0, 1, 2, 3}, {},
        {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
         "ViewLayer.Combined.A"});
    const OIIO::ImageBuf out = display(cycles, {kConfig, "sRGB", "sRGB"});
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_EQ(out.spec().channelnames, (std::vector<std::string>{"R", "G", "B", "A"}));
    EXPECT_NEAR(out.getchannel(1, 1, 0, 0), 0.461356f, 1e-4f);
    EXPECT_NEAR(out.getchannel(1, 1, 0, 3), 0.5f, 0.f);
}

TEST(Display, ErrorsNameTheDisplayViewAndConfig)
{
    OIIO::ImageBuf out = display(gray_rgba(0.18f), {kConfig, "P3", ""});
    ASSERT_TRUE(out.has_error());
    EXPECT_EQ(out.geterror(),
              "display 'P3' is not in OCIO config " + kConfig + " (displays: sRGB)");
    out = display(gray_rgba(0.18f), {kConfig, "sRGB", "ACES"});
    EXPECT_EQ(out.geterror(), "view 'ACES' of display 'sRGB' is not in OCIO config " + kConfig +
                                  " (views: sRGB, Filmic, Raw)");
    out = display(gray_rgba(0.18f), {"/nonexistent/config.ocio", "", ""});
    EXPECT_NE(out.geterror().find("OCIO config /nonexistent/config.ocio: "), std::string::npos);
}

}  // namespace
}  // namespace statmc
