// How images holding statistics are stored: float32 channels (half overflows at 65504 and
// loses counts above 2048) and lossless compression (a lossy codec would bias the test).
#pragma once

#include <string_view>

#include <OpenImageIO/imageio.h>

namespace statmc::layers {

/// Whether `compression` (an OIIO "compression" value such as "zip" or "dwaa:45") loses
/// nothing.
bool is_lossless_compression(std::string_view compression);

/// Rewrites `spec` for writing under the contract: every channel float32, scanline, and
/// zip compression unless a lossless one is already chosen.
void apply_storage_rules(OIIO::ImageSpec& spec);

}  // namespace statmc::layers
