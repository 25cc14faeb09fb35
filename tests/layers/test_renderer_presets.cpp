// Which renderer a header says wrote the file: the contract first, one preset at most,
// and a plain render claimed by none.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/renderer_presets.h"

namespace {

using statmc::layers::detect_renderer;

OIIO::ImageSpec spec_with(const std::vector<std::string>& channels)
{
    OIIO::ImageSpec spec(4, 3, int(channels.size()), OIIO::TypeFloat);
    spec.channelnames = channels;
    return spec;
}

TEST(RendererPresets, EachSignatureIsRecognised)
{
    EXPECT_EQ(detect_renderer(spec_with({"R", "G", "B"})).preset, "");
    EXPECT_EQ(detect_renderer(spec_with({"R", "G", "B", "sampleCount.Y"})).preset, "statmc");
    EXPECT_EQ(detect_renderer(spec_with({"R", "G", "B", "mse.r", "sampleCount"})).preset,
              "renderman");
    EXPECT_EQ(detect_renderer(spec_with({"R", "G", "B", "RelativeVariance.R"})).preset, "pbrt-v4");
    const auto cycles = detect_renderer(spec_with({"View Layer.Combined.R"}));
    EXPECT_EQ(cycles.preset, "cycles");
    EXPECT_EQ(cycles.evidence, "channel View Layer.Combined.R");
}

TEST(RendererPresets, TheContractTakesPrecedenceOverChannelsItCarries)
{
    // --passes keeps a multilayer file's other passes beside the statistics it writes.
    OIIO::ImageSpec spec = spec_with({"R", "G", "B", "ViewLayer.Combined.R", "mse.r"});
    spec.attribute("statmc:formatVersion", 2);
    EXPECT_EQ(detect_renderer(spec).preset, "statmc");
}

TEST(RendererPresets, ASingleLayerBlenderFileIsAPlainRender)
{
    OIIO::ImageSpec spec = spec_with({"R", "G", "B", "A"});
    spec.attribute("cycles.ViewLayer.samples", "8");
    EXPECT_EQ(detect_renderer(spec).preset, "");
}

TEST(RendererPresets, TwoViewLayersAreRefusedNamingThem)
{
    OIIO::ImageBuf two(spec_with({"A.Combined.R", "A.Combined.G", "A.Combined.B", "B.Combined.R",
                                  "B.Combined.G", "B.Combined.B"}));
    try {
        statmc::layers::render_from_preset(two, "cycles");
        ADD_FAILURE() << "two view layers were accepted";
    } catch (const statmc::layers::LayerError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "the image holds view layers A, B; keep the channels of one with --ch "
                  "(docs/renderers.md)");
    }
}

}  // namespace
