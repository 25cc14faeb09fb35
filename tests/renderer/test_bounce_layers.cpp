// The per-bounce layers in the output EXR: what statmc-render writes is what the film
// accumulated, bit for bit, under the contract's names, and `statmc --denoise:aov=...`
// denoises one of them as core's filter does.
#include <cmath>
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/layers/statistics_layers.h"

#include "renderer_test_support.h"
#include "same_bits.h"
#include "statmc/render/camera.h"
#include "statmc/render/exr_output.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"

using namespace statmc::render;
using statmc::render::test::ScratchDir;
using statmc::test::same_bits;

namespace {

constexpr int kW = 24, kH = 16, kSpp = 16, kSeed = 7;

// The in-process twin of `statmc-render room.pbrt --spp 16 --seed 7 --rr acrr --mis selective
// --bounce-layers`.
std::unique_ptr<Film> render_room(const std::string& text)
{
    IntegratorSettings integrator;
    integrator.roulette.mode = RouletteMode::Acrr;
    integrator.mis.mode = MisMode::Selective;
    return statmc::render::test::render_scene(parse_scene_string(text, "room.pbrt"), kW, kH, kSpp,
                                              kSeed, 0, integrator, {}, true)
        .film;
}

int run(const std::string& cmd) { return std::system((cmd + " > /dev/null 2>&1").c_str()); }

OIIO::ImageBuf read(const std::string& path)
{
    OIIO::ImageBuf buf(path);
    EXPECT_TRUE(buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << buf.geterror();
    return buf;
}

}  // namespace

TEST(BounceLayers, RoundTripThroughTheExrAndStatmcDenoise)
{
    ScratchDir dir("bounce-layers");
    const std::string text = statmc::render::test::test_room();
    const std::string scene = dir.write("room.pbrt", text);
    const std::string out = dir.file("out.exr"), den = dir.file("den.exr");
    ASSERT_EQ(run(std::string("\"") + STATMC_RENDER_EXE + "\" \"" + scene + "\" -o \"" + out +
                  "\" --resolution " + std::to_string(kW) + "x" + std::to_string(kH) +
                  " --spp 16 --seed 7 --rr acrr --mis selective --bounce-layers -q"),
              0);
    const auto film = render_room(text);
    const BounceLayout& layout = film->bounces->layout();
    ASSERT_EQ(layout.quantities(), 5 + 12);  // L_0..L_4, two win counts at 6 vertices
    const OIIO::ImageBuf back = read(out);
    const auto groups = film->bounces->group_planes();
    for (int q = 0; q < layout.quantities(); ++q) {
        const std::string aov = layout.aov(q);
        const statmc::StatisticsView expected = BounceStatistics::quantity_view(groups, q);
        const statmc::StatisticsView got = statmc::layers::read_statistics(back, aov);
        ASSERT_EQ(got.channels, 1) << aov;
        ASSERT_TRUE(got.has_box_cox()) << aov;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                ASSERT_TRUE(same_bits(expected.mean[0](x, y), got.mean[0](x, y)))
                    << aov << " " << x << "," << y;
                ASSERT_TRUE(same_bits(expected.variance[0](x, y), got.variance[0](x, y))) << aov;
                ASSERT_TRUE(same_bits(expected.bc_mean[0](x, y), got.bc_mean[0](x, y))) << aov;
                ASSERT_TRUE(same_bits(expected.bc_variance[0](x, y), got.bc_variance[0](x, y)))
                    << aov;
                ASSERT_TRUE(same_bits(expected.bc_moment3[0](x, y), got.bc_moment3[0](x, y)))
                    << aov;
                ASSERT_EQ(got.count(x, y), float(kSpp));
            }
    }
    EXPECT_GE(back.spec().channelindex("bounce4L.boxcoxM3.Y"), 0);
    EXPECT_GE(back.spec().channelindex("bounce5BsdfWins.variance.Y"), 0);
    EXPECT_LT(back.spec().channelindex("bounce5L.Y"), 0);

    // statmc denoises bounce1L alone: as core's filter does with the film's guides, and
    // everything else is left as it was. (method=paper: the paper's filter bit for bit, as
    // the renderer uses for these quantities.)
    ASSERT_EQ(run(std::string("\"") + STATMC_CLI_EXE + "\" \"" + out +
                  "\" --denoise:aov=bounce1L:method=paper -o \"" + den + "\""),
              0);
    const OIIO::ImageBuf denoised = read(den);
    const statmc::StatisticsView q1 = BounceStatistics::quantity_view(groups, layout.luminance(1));
    const std::vector<float> albedo = film->albedo(), normal = film->normal();
    statmc::Guides guides;
    const std::size_t n = std::size_t(kW) * kH;
    for (int c = 0; c < 3; ++c) {
        guides.albedo[c] = statmc::dense_plane(albedo.data() + c * n, kW);
        guides.normal[c] = statmc::dense_plane(normal.data() + c * n, kW);
    }
    std::vector<float> expected(n);
    statmc::filter(statmc::estimators_from_statistics(q1, statmc::TestDomain::BoxCox), guides,
                   statmc::DenoiseOptions::paper(), {statmc::dense_plane(expected.data(), kW)}, {},
                   1);
    const int ch = denoised.spec().channelindex("bounce1L.Y"),
              r = denoised.spec().channelindex("R");
    const int other = denoised.spec().channelindex("bounce2L.Y");
    ASSERT_GE(ch, 0);
    int changed = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            EXPECT_FLOAT_EQ(denoised.getchannel(x, y, 0, ch), expected[std::size_t(y) * kW + x])
                << x << "," << y;
            // Only changes beyond float rounding count.
            const float before = back.getchannel(x, y, 0, ch),
                        after = denoised.getchannel(x, y, 0, ch);
            changed += std::abs(after - before) > 1e-6f * std::max(std::abs(before), 1e-6f);
            EXPECT_EQ(denoised.getchannel(x, y, 0, r), back.getchannel(x, y, 0, r));
            EXPECT_EQ(denoised.getchannel(x, y, 0, other), back.getchannel(x, y, 0, other));
        }
    EXPECT_GT(changed, kW * kH / 4);  // the filter did average (measured: 135 of 384 pixels)
}
