// Other renderers' files (docs/renderers.md): a RenderMan or pbrt-v4 file must denoise
// exactly as the contract file holding the same numbers under statmc's names, keep its
// own channel names, and be refused, with what is missing, when it is partial, ambiguous
// or holds no statistics.
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/denoise/denoise.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"
#include "test_images.h"

namespace statmc {
namespace {

using test::channel_value;

constexpr int kW = 24, kH = 16;

// The contract image of a noisy frame with a variance AOV and guides; `constant_count`
// gives every pixel that many samples (pbrt-v4 writes one count in the header).
OIIO::ImageBuf contract_image(const char* variance_of, int constant_count = 0)
{
    StatisticsPlanes stats = test::variance_aov(test::noisy_statistics(kW, kH, 8, 17));
    if (constant_count > 0)
        stats.count.assign(stats.count.size(), float(constant_count));
    const test::GuideData guides = test::make_guides(kW, kH, 5);
    OIIO::ImageBuf image = layers::make_statistics_image(stats, {}, guides.planes());
    image.specmod().attribute(layers::attr::kVariance, variance_of);
    return image;
}

// `contract` as another renderer writes it: channels renamed by `names` (others dropped)
// and no statmc: attribute left.
OIIO::ImageBuf renderer_image(const OIIO::ImageBuf& contract,
                              const std::map<std::string, std::string>& names)
{
    std::vector<int> order;
    std::vector<std::string> renamed;
    for (const auto& [from, to] : names) {
        order.push_back(contract.spec().channelindex(from));
        EXPECT_GE(order.back(), 0) << from;
        renamed.push_back(to);
    }
    OIIO::ImageBuf out =
        OIIO::ImageBufAlgo::channels(contract, int(order.size()), order, {}, renamed);
    EXPECT_FALSE(out.has_error()) << out.geterror();
    for (const char* name : {layers::attr::kFormatVersion, layers::attr::kVariance,
                             layers::attr::kBoxCoxLambda, layers::attr::kSpp})
        out.specmod().erase_attribute(name);
    return out;
}

const std::map<std::string, std::string> kRenderManNames = {
    {"R", "R"},
    {"G", "G"},
    {"B", "B"},
    {"variance.R", "mse.r"},
    {"variance.G", "mse.g"},
    {"variance.B", "mse.b"},
    {"sampleCount.Y", "sampleCount"},
    {"albedo.R", "albedo.r"},
    {"albedo.G", "albedo.g"},
    {"albedo.B", "albedo.b"},
    {"normal.X", "normal.x"},
    {"normal.Y", "normal.y"},
    {"normal.Z", "normal.z"},
};

const std::map<std::string, std::string> kPbrtNames = {
    {"R", "R"},
    {"G", "G"},
    {"B", "B"},
    {"variance.R", "Variance.R"},
    {"variance.G", "Variance.G"},
    {"variance.B", "Variance.B"},
    {"albedo.R", "Albedo.R"},
    {"albedo.G", "Albedo.G"},
    {"albedo.B", "Albedo.B"},
    {"normal.X", "Ns.X"},
    {"normal.Y", "Ns.Y"},
    {"normal.Z", "Ns.Z"},
};

DenoiseImageOptions options()
{
    DenoiseImageOptions opt;
    opt.filter.radius = 4;
    return opt;
}

void expect_same_beauty(const OIIO::ImageBuf& a, const OIIO::ImageBuf& b)
{
    for (const char* c : {"R", "G", "B"})
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_TRUE(test::same_bits(channel_value(a, c, x, y), channel_value(b, c, x, y)))
                    << c << " at (" << x << ", " << y << ")";
}

std::string error_of(const OIIO::ImageBuf& src, const DenoiseImageOptions& opt)
{
    const OIIO::ImageBuf out = denoise(src, opt);
    EXPECT_TRUE(out.has_error());
    return out.geterror();
}

TEST(DenoisePresets, RenderManDenoisesAsItsContractTwinAndKeepsItsNames)
{
    const OIIO::ImageBuf contract = contract_image(layers::kVarianceOfMean);
    const OIIO::ImageBuf renderman = renderer_image(contract, kRenderManNames);
    const OIIO::ImageBuf expected = denoise(contract, options());
    ASSERT_FALSE(expected.has_error()) << expected.geterror();
    const OIIO::ImageBuf got = denoise(renderman, options());
    ASSERT_FALSE(got.has_error()) << got.geterror();
    expect_same_beauty(got, expected);
    // The guides steered it: without them the result differs.
    DenoiseImageOptions unguided = options();
    unguided.guides.albedo = unguided.guides.normal = GuideUse::Off;
    const OIIO::ImageBuf plain = denoise(contract, unguided);
    bool differs = false;
    for (int x = 0; x < kW && !differs; ++x)
        differs = !test::same_bits(channel_value(plain, "R", x, 5), channel_value(got, "R", x, 5));
    EXPECT_TRUE(differs);

    EXPECT_EQ(got.spec().channelnames, renderman.spec().channelnames);
    EXPECT_EQ(channel_value(got, "mse.g", 3, 4), channel_value(renderman, "mse.g", 3, 4));
    EXPECT_EQ(got.spec().get_int_attribute(layers::attr::kDenoised), 1);
}

TEST(DenoisePresets, PbrtV4TakesItsCountFromTheHeader)
{
    const OIIO::ImageBuf contract = contract_image(layers::kVarianceOfSample, 16);
    OIIO::ImageBuf pbrt = renderer_image(contract, kPbrtNames);
    pbrt.specmod().attribute("samplesPerPixel", 16);
    const OIIO::ImageBuf expected = denoise(contract, options());
    const OIIO::ImageBuf got = denoise(pbrt, options());
    ASSERT_FALSE(got.has_error()) << got.geterror();
    expect_same_beauty(got, expected);
    EXPECT_EQ(got.spec().channelindex("sampleCount.Y"), -1);

    // Named explicitly, the same; named wrongly, what the other preset lacks is listed.
    DenoiseImageOptions named = options();
    named.from = "pbrt-v4";
    expect_same_beauty(denoise(pbrt, named), expected);
    named.from = "renderman";
    const std::string why = error_of(pbrt, named);
    EXPECT_NE(why.find("Pixar RenderMan"), std::string::npos) << why;
    EXPECT_NE(why.find("channels mse.r, mse.g, mse.b"), std::string::npos) << why;
    EXPECT_NE(why.find("channels sampleCount"), std::string::npos) << why;
}

TEST(DenoisePresets, APartialMatchListsWhatIsMissing)
{
    const OIIO::ImageBuf contract = contract_image(layers::kVarianceOfSample, 16);
    const OIIO::ImageBuf pbrt = renderer_image(contract, kPbrtNames);
    OIIO::ImageBuf relative = pbrt;
    relative = OIIO::ImageBufAlgo::channels(
        pbrt, pbrt.nchannels() + 1,
        [&] {
            std::vector<int> o;
            for (int c = 0; c < pbrt.nchannels(); ++c)
                o.push_back(c);
            o.push_back(-1);
            return o;
        }(),
        {},
        [&] {
            std::vector<std::string> n = pbrt.spec().channelnames;
            n.push_back("RelativeVariance.R");
            return n;
        }());
    const std::string why = error_of(relative, options());  // no samplesPerPixel
    EXPECT_NE(why.find("from=pbrt-v4"), std::string::npos) << why;
    EXPECT_NE(why.find("header attribute samplesPerPixel"), std::string::npos) << why;

    std::map<std::string, std::string> no_count = kRenderManNames;
    no_count.erase("sampleCount.Y");
    const std::string rman = error_of(renderer_image(contract, no_count), options());
    EXPECT_NE(rman.find("from=renderman) needs channels sampleCount"), std::string::npos) << rman;
}

TEST(DenoisePresets, AnAmbiguousImageIsRefusedNamingBothRenderers)
{
    const OIIO::ImageBuf contract = contract_image(layers::kVarianceOfMean, 16);
    std::map<std::string, std::string> both = kRenderManNames;
    both["depth.Z"] = "RelativeVariance.R";
    OIIO::ImageBuf image = renderer_image(contract, both);
    const std::string why = error_of(image, options());
    EXPECT_NE(why.find("more than one renderer's: renderman (channel mse."), std::string::npos)
        << why;
    EXPECT_NE(why.find("pbrt-v4 (channel RelativeVariance.R)"), std::string::npos) << why;
    DenoiseImageOptions named = options();
    named.from = "renderman";
    const OIIO::ImageBuf got = denoise(image, named);
    ASSERT_FALSE(got.has_error()) << got.geterror();
    expect_same_beauty(got, denoise(contract, options()));
}

TEST(DenoisePresets, CyclesHoldsNoStatisticsAndSaysHowToGetThem)
{
    const OIIO::ImageBuf contract = contract_image(layers::kVarianceOfSample);
    const OIIO::ImageBuf cycles =
        renderer_image(contract, {{"R", "ViewLayer.Combined.R"},
                                  {"G", "ViewLayer.Combined.G"},
                                  {"B", "ViewLayer.Combined.B"},
                                  {"albedo.R", "ViewLayer.Denoising Albedo.R"},
                                  {"albedo.G", "ViewLayer.Denoising Albedo.G"},
                                  {"albedo.B", "ViewLayer.Denoising Albedo.B"}});
    const std::string why = error_of(cycles, options());
    EXPECT_NE(why.find("Cycles writes no per-pixel variance"), std::string::npos) << why;
    EXPECT_NE(why.find("--passes --denoise"), std::string::npos) << why;
}

TEST(DenoisePresets, AnUnknownPresetIsRefusedByName)
{
    DenoiseImageOptions opt = options();
    opt.from = "arnold";
    EXPECT_NE(opt.validate().find("from must be auto or a renderer preset, got 'arnold'"),
              std::string::npos);
}

}  // namespace
}  // namespace statmc
