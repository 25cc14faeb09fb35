#include "statmc/layers/storage_rules.h"

#include <string>

namespace statmc::layers {

bool is_lossless_compression(std::string_view compression)
{
    // OIIO spells a level after a colon ("zip:4"); only the codec matters here.
    const std::string_view codec = compression.substr(0, compression.find(':'));
    return codec == "none" || codec == "rle" || codec == "zip" || codec == "zips" || codec == "piz";
}

void apply_storage_rules(OIIO::ImageSpec& spec)
{
    spec.set_format(OIIO::TypeDesc::FLOAT);
    spec.channelformats.clear();
    // Scanline files are what every EXR reader handles (docs/ecosystem.md §3 checklist).
    spec.tile_width = spec.tile_height = spec.tile_depth = 0;
    if (!is_lossless_compression(spec.get_string_attribute("compression")))
        spec.attribute("compression", "zip");
}

}  // namespace statmc::layers
