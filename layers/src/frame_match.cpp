#include "statmc/layers/frame_match.h"

#include <OpenImageIO/strutil.h>

#include "statmc/layers/layer_error.h"

namespace statmc::layers {

void require_same_frame(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b, const std::string& these)
{
    if (a.width != b.width || a.height != b.height)
        throw LayerError(OIIO::Strutil::fmt::format("{} differ in resolution: {}x{} vs {}x{}", these,
                                                    a.width, a.height, b.width, b.height));
    if (a.x != b.x || a.y != b.y)
        throw LayerError(OIIO::Strutil::fmt::format("{} differ in data window: origin ({}, {}) vs ({}, {})",
                                                    these, a.x, a.y, b.x, b.y));
}

}  // namespace statmc::layers
