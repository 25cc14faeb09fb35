// The one exception the layer contract throws: a message fit to show a user as is.
#pragma once

#include <stdexcept>
#include <string>

namespace statmc::layers {

/// An image does not follow the layer contract (a missing or partial layer, a bad header
/// attribute, pixels that are not statistics). Operators turn it into an ImageBuf error.
class LayerError : public std::runtime_error {
public:
    explicit LayerError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace statmc::layers
