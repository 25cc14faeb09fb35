// Finding a layer's channels in an ImageSpec by name. OIIO reorders channels on read
// (docs/ecosystem.md pitfall 5), so an index is never assumed, always looked up.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <OpenImageIO/imageio.h>

namespace statmc::layers {

/// Indices of `layer`'s channels with the given suffixes, −1 where a channel is absent.
std::vector<int> channel_indices(const OIIO::ImageSpec& spec, std::string_view layer,
                                 const std::vector<std::string>& suffixes);

/// Whether every index is present, or none is.
bool all_present(const std::vector<int>& indices);
bool none_present(const std::vector<int>& indices);

/// "variance (channels variance.R, variance.G, variance.B)"; the unprefixed layer is
/// called "beauty".
std::string describe_layer(std::string_view layer, const std::vector<std::string>& suffixes);

/// The distinct layers of `spec` in channel order ("" for unprefixed channels), the
/// layer of "bounce1.variance.R" being "bounce1.variance".
std::vector<std::string> layers_in(const OIIO::ImageSpec& spec);

/// "missing <kind> <describe_layer>[; <why>]", followed by the layers the image does
/// have and a hint when one of them differs only in case.
std::string missing_layer_message(const OIIO::ImageSpec& spec, std::string_view layer,
                                  const std::vector<std::string>& suffixes,
                                  std::string_view kind = "layer", std::string_view why = "");

/// The indices of a complete layer. Throws LayerError naming the layer when it is absent
/// or names the missing channels when it is only partly present.
std::vector<int> require_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                               const std::vector<std::string>& suffixes);

/// Like require_layer, but an entirely absent layer gives an empty vector.
std::vector<int> optional_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                                const std::vector<std::string>& suffixes);

}  // namespace statmc::layers
