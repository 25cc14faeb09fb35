// Whether two images can be samples of one frame: the check every multi-input operator
// (passes, merge) makes before combining pixels.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// Throws LayerError unless `a` and `b` have the same resolution and data window;
/// `these` names the pair in the message, e.g. "render 1 (b.exr) and render 0 (a.exr)".
void require_same_frame(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b, const std::string& these);

}  // namespace statmc::layers
