// oiiotool's channel lists (--ch, -i:ch=): "R,G,B", indices "2,0", renames
// "var.R=variance.R" and constants "A=1" or "=0.5", turned into ImageBufAlgo::channels'
// arguments.
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

namespace statmc::tool {

struct ChannelSelection {
    std::vector<int> order;          ///< source channel per output channel; -1 = constant
    std::vector<float> values;       ///< the constant where order is -1
    std::vector<std::string> names;  ///< new names; "" keeps the source's
};

/// Parses `list` against the channels of `spec`. Throws HostError "<what>: ..." for a
/// channel the image lacks (naming the ones it has) and an index out of range, where
/// oiiotool would warn and fill with zero.
ChannelSelection parse_channel_selection(const std::string& list, const OIIO::ImageSpec& spec,
                                         const std::string& what);

/// `image` with the channels `list` selects (ImageBufAlgo::channels); parse errors throw
/// as parse_channel_selection does, OIIO's are left on the result.
OIIO::ImageBuf select_channels(const OIIO::ImageBuf& image, const std::string& list,
                               const std::string& what, int nthreads);

}  // namespace statmc::tool
