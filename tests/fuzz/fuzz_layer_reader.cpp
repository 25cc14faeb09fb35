// Bytes as an EXR → the layer contract's reader (the headers' checks and budget, every part
// and MIP level decoded by the isolated decoder, layers/isolated_decode.h) → the statistics, guide
// and AOV lookups → the denoise operator, in its default and in the paper's form. Every failure
// must be a FileError or LayerError, or an error on the destination image; a crash, a hang or a
// runaway allocation is a finding. A decoder that died or hung on an input is no finding (it is
// what the isolation is for), but is counted, and the count printed at exit.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include <OpenImageIO/imageio.h>

#include "fuzz_input.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_validation.h"

namespace {

int g_decoder_deaths = 0;

void report_decoder_deaths()
{
    std::fprintf(stderr, "fuzz_layer_reader: the isolated decoder died or hung on %d inputs\n",
                 g_decoder_deaths);
}

// The reader's own words after the file's name (an attribute's name in a header error can
// hold any text, the fuzzer's dictionary included).
bool decoder_died(const std::string& message, const std::string& path)
{
    const std::string own = ": damaged OpenEXR file: the decoder ";
    return message.compare(path.size(), own.size(), own) == 0;
}

void look_up_layers(const OIIO::ImageBuf& image)
{
    const OIIO::ImageSpec& spec = image.spec();
    statmc::layers::layers_in(spec);
    // Each lookup on its own: an incomplete layer is a LayerError, which the operators turn
    // into an error on their destination.
    try {
        const auto channels = statmc::layers::find_statistics(spec);
        statmc::layers::validate_statistics(image, channels);
    } catch (const statmc::layers::LayerError&) {
    }
    for (const auto& [layer, colour] : {std::pair{statmc::layers::kAlbedoLayer, true},
                                        std::pair{statmc::layers::kNormalLayer, false}}) {
        try {
            statmc::layers::find_guide_layer(spec, layer, colour);
        } catch (const statmc::layers::LayerError&) {
        }
    }
}

void denoise_with(const OIIO::ImageBuf& image, statmc::DenoiseImageOptions options)
{
    options.filter.radius = 3;  // the filter's logic, not its cost, is under test
    options.nonfinite = statmc::NonfinitePolicy::Zero;
    OIIO::ImageBuf result;
    statmc::denoise(result, image, options, {}, 1);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    static const bool single_threaded = OIIO::attribute("threads", 1);
    static const int reported = std::atexit(report_decoder_deaths);
    (void)single_threaded;
    (void)reported;
    statmc::layers::ReadOptions options;
    options.max_memory = 16 << 20;  // small images only: a larger header is refused
    std::vector<OIIO::ImageBuf> parts;
    statmc::layers::MipLevels mip_levels;  // read as a copy reads them
    const std::string path = statmc::fuzz::as_file(data, size, ".exr");
    try {
        parts = statmc::layers::read_image_subimages(path, options, &mip_levels);
    } catch (const statmc::layers::FileError& e) {
        g_decoder_deaths += decoder_died(e.what(), path);
        return 0;
    }
    const statmc::DenoiseImageOptions the_default, paper = statmc::DenoiseImageOptions::paper();
    for (const OIIO::ImageBuf& part : parts) {
        look_up_layers(part);
        denoise_with(part, the_default);
        denoise_with(part, paper);
    }
    return 0;
}
