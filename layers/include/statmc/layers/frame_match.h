// Whether images can be samples of one frame: the check every multi-input operator
// (passes, merge) makes before combining pixels, and how those operators name an input.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// Throws LayerError unless `a` and `b` have the same resolution and data window;
/// `these` names the pair in the message, e.g. "render 1 (b.exr) and render 0 (a.exr)".
void require_same_frame(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b,
                        const std::string& these);

/// "render 2 (b.exr)": input `k` named by `noun`, with its file name when it has one.
std::string input_label(std::string_view noun, std::size_t k, const OIIO::ImageBuf* input);

/// Throws LayerError unless `a` and `b` have the same frame (require_same_frame) and channel
/// names (in any order); the message names both and the channels only one side has.
void require_matching_specs(const OIIO::ImageSpec& a, const std::string& a_label,
                            const OIIO::ImageSpec& b, const std::string& b_label);

/// Throws LayerError unless every input has the frame (require_same_frame) and the channel
/// names (in any order) of input 0; the message names the channels only one side has.
/// The inputs must be initialized.
void require_matching_inputs(const std::vector<const OIIO::ImageBuf*>& inputs,
                             std::string_view noun);

}  // namespace statmc::layers
