// The denoise operator's front: the input checked, and another renderer's file (and its
// sequence's frames) brought to the layer contract's names once, so that every later step
// of the pipeline reads one form.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/denoise/denoise.h"

namespace statmc::denoising {

/// Throws std::invalid_argument for an image the operator cannot read at all.
void check_input(const OIIO::ImageBuf& src);

/// A renderer's frame and its neighbours under the contract's names.
struct ContractInput {
    OIIO::ImageBuf image;  ///< float pixels: denoised in place
    std::vector<OIIO::ImageBuf> previous, next;
    /// (contract channel, renderer channel) of every renamed channel of `image`.
    std::vector<std::pair<std::string, std::string>> renamed;

    FrameNeighbours neighbours() const;
};

/// Whose channel names `in` has (`from`: auto or a preset, layers/renderer_presets.h):
/// empty for the contract's own, else the preset.
std::string renderer_of(const OIIO::ImageBuf& in, const std::string& from);
/// `in` and `neighbours` imported through `preset`.
ContractInput imported_input(const OIIO::ImageBuf& in, const FrameNeighbours& neighbours,
                             const std::string& preset);
/// `original` with the denoised means of `opt`'s layers (and the diagnostics, when asked
/// for) of `denoised` written back under the renderer's own channel names, every other
/// channel kept as it was.
OIIO::ImageBuf with_renderer_names(const OIIO::ImageBuf& original, const OIIO::ImageBuf& denoised,
                                   const ContractInput& input, const DenoiseImageOptions& opt);

}  // namespace statmc::denoising
