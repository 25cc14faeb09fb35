// Feature layers that guide the filter: albedo, normal (and depth, stored but not used
// by the filter yet).
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/filter.h"
#include "statmc/core/plane.h"

namespace statmc::layers {

/// Guide planes of one image; an absent guide has null planes.
struct GuidePlanes {
    std::array<ConstPlane, 3> albedo{};
    std::array<ConstPlane, 3> normal{};
    ConstPlane depth{};
    std::array<ConstPlane, 2> motion{};  ///< motion.X, motion.Y (kMotionLayer)
    /// albedoVariance.Y, normalVariance.Y: each guide's per-sample variance summed over its
    /// channels (guide_variance_layer), null when absent.
    ConstPlane albedo_variance{};
    ConstPlane normal_variance{};

    /// The guides the core filter takes.
    Guides core() const { return {albedo, normal, albedo_variance, normal_variance}; }
};

/// The plane of `guide_layer`'s variance in `buf` (local float pixels), null when absent.
ConstPlane guide_variance_plane(const OIIO::ImageBuf& buf, std::string_view guide_layer);

/// Indices of a three-channel guide layer. Colour suffixes R,G,B are tried first for
/// albedo-like layers and X,Y,Z first otherwise (`prefer_colour`); either is accepted, so
/// an `N.R/G/B` normal works. Empty when the layer is absent; throws LayerError when it
/// is only partly present.
std::vector<int> find_guide_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                                  bool prefer_colour);

/// find_guide_layer, but an absent layer throws LayerError:
/// "missing guide layer albedo (channels albedo.R, albedo.G, albedo.B)".
std::vector<int> require_guide_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                                     bool prefer_colour);

/// The three planes at `indices` of `buf` (local float pixels, see float_pixels.h).
std::array<ConstPlane, 3> guide_planes(const OIIO::ImageBuf& buf, const std::vector<int>& indices);

/// The planes of the motion layer (motion.X, motion.Y) of `buf` (local float pixels); both
/// null when the layer is absent. Throws LayerError when it is only partly present.
std::array<ConstPlane, 2> motion_planes(const OIIO::ImageBuf& buf);

}  // namespace statmc::layers
