#include "denoise_input.h"

#include <stdexcept>

#include "denoised_image.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/renderer_presets.h"
#include "statmc/layers/statistics_layers.h"

namespace statmc::denoising {

namespace {

// The channel `from` holds under `to`'s name, over the whole data window.
void copy_channel(const OIIO::ImageBuf& from, const std::string& from_name, OIIO::ImageBuf& to,
                  const std::string& to_name)
{
    OIIO::ROI source = from.roi(), target = to.roi();
    source.chbegin = from.spec().channelindex(from_name);
    target.chbegin = to.spec().channelindex(to_name);
    source.chend = source.chbegin + 1;
    target.chend = target.chbegin + 1;
    std::vector<float> values(source.npixels());
    if (!from.get_pixels(source, OIIO::TypeFloat, values.data()) ||
        !to.set_pixels(target, OIIO::TypeFloat, values.data()))
        throw std::runtime_error("cannot copy the denoised channel " + from_name + " to " +
                                 to_name);
}

std::vector<OIIO::ImageBuf> imported_frames(const std::vector<const OIIO::ImageBuf*>& frames,
                                            const std::string& preset)
{
    std::vector<OIIO::ImageBuf> imported;
    for (const OIIO::ImageBuf* frame : frames)
        imported.push_back(layers::statistics_from_preset(*frame, preset).image);
    return imported;
}

}  // namespace

void check_input(const OIIO::ImageBuf& src)
{
    if (!src.initialized())
        throw std::invalid_argument("uninitialized input image");
    if (src.deep())
        throw std::invalid_argument("deep images are not supported");
    if (src.spec().depth > 1)
        throw std::invalid_argument("volume images are not supported");
}

FrameNeighbours ContractInput::neighbours() const
{
    FrameNeighbours n;
    for (const OIIO::ImageBuf& frame : previous)
        n.previous.push_back(&frame);
    for (const OIIO::ImageBuf& frame : next)
        n.next.push_back(&frame);
    return n;
}

std::string renderer_of(const OIIO::ImageBuf& in, const std::string& from)
{
    const std::string preset = layers::resolve_renderer_preset(in.spec(), from);
    return preset == "statmc" ? std::string() : preset;
}

ContractInput imported_input(const OIIO::ImageBuf& in, const FrameNeighbours& neighbours,
                             const std::string& preset)
{
    layers::ImportedImage frame = layers::statistics_from_preset(in, preset);
    ContractInput input;
    input.image = std::move(frame.image);
    input.renamed = std::move(frame.renamed);
    input.previous = imported_frames(neighbours.previous, preset);
    input.next = imported_frames(neighbours.next, preset);
    return input;
}

OIIO::ImageBuf with_renderer_names(const OIIO::ImageBuf& original, const OIIO::ImageBuf& denoised,
                                   const ContractInput& input, const DenoiseImageOptions& opt)
{
    OIIO::ImageBuf result;
    if (!result.copy(original, OIIO::TypeFloat))
        throw std::runtime_error("cannot copy the input: " + result.geterror());
    const OIIO::ImageSpec& spec = denoised.spec();
    std::vector<std::string> denoised_aovs = {opt.aov};
    denoised_aovs.insert(denoised_aovs.end(), opt.aovs.begin(), opt.aovs.end());
    for (const std::string& aov : denoised_aovs)
        for (int c : layers::find_statistics(spec, aov).mean)
            for (const auto& [contract_name, source_name] : input.renamed)
                if (contract_name == spec.channelnames[c])
                    copy_channel(denoised, contract_name, result, source_name);
    if (opt.diagnostics) {
        int members = -1, effective = -1;
        result = with_diagnostics_channels(result, opt.aov, members, effective);
        for (int c : {members, effective})
            copy_channel(denoised, result.spec().channelnames[c], result,
                         result.spec().channelnames[c]);
    }
    return result;
}

}  // namespace statmc::denoising
