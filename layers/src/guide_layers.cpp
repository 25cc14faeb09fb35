#include "statmc/layers/guide_layers.h"

#include "statmc/layers/float_pixels.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"

namespace statmc::layers {

namespace {

// Renderers disagree on a normal's suffixes (normal.X vs Arnold's N.R), so both are read.
std::pair<const std::vector<std::string>*, const std::vector<std::string>*>
suffix_order(bool prefer_colour)
{
    if (prefer_colour)
        return {&colour_suffixes(), &vector_suffixes()};
    return {&vector_suffixes(), &colour_suffixes()};
}

}  // namespace

std::vector<int> find_guide_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                                  bool prefer_colour)
{
    const auto [first, second] = suffix_order(prefer_colour);
    const std::vector<int> a = channel_indices(spec, layer, *first);
    if (all_present(a))
        return a;
    const std::vector<int> b = channel_indices(spec, layer, *second);
    if (all_present(b))
        return b;
    if (none_present(a) && none_present(b))
        return {};
    // Partly present: let the suffix set with more channels name what is missing.
    const auto present = [](const std::vector<int>& v) {
        int n = 0;
        for (int i : v)
            n += i >= 0;
        return n;
    };
    return optional_layer(spec, layer, present(b) > present(a) ? *second : *first);
}

std::vector<int> require_guide_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                                     bool prefer_colour)
{
    std::vector<int> indices = find_guide_layer(spec, layer, prefer_colour);
    if (indices.empty())
        throw LayerError(
            missing_layer_message(spec, layer, *suffix_order(prefer_colour).first, "guide layer"));
    return indices;
}

std::array<ConstPlane, 3> guide_planes(const OIIO::ImageBuf& buf, const std::vector<int>& indices)
{
    if (indices.size() != 3)
        throw LayerError("a guide layer has 3 channels");
    return {channel_plane(buf, indices[0]), channel_plane(buf, indices[1]),
            channel_plane(buf, indices[2])};
}

ConstPlane guide_variance_plane(const OIIO::ImageBuf& buf, std::string_view guide_layer)
{
    static const std::vector<std::string> kY = {"Y"};
    const std::vector<int> index =
        optional_layer(buf.spec(), guide_variance_layer(guide_layer), kY);
    return index.empty() ? ConstPlane{} : channel_plane(buf, index[0]);
}

std::array<ConstPlane, 2> motion_planes(const OIIO::ImageBuf& buf)
{
    static const std::vector<std::string> kSuffixes = {"X", "Y"};
    const std::vector<int> indices = optional_layer(buf.spec(), kMotionLayer, kSuffixes);
    if (indices.empty())
        return {};
    return {channel_plane(buf, indices[0]), channel_plane(buf, indices[1])};
}

}  // namespace statmc::layers
