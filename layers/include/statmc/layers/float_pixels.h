// Core planes over an ImageBuf's own memory: local float pixels are viewed in place,
// with strides, instead of being copied into planar buffers.
#pragma once

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/plane.h"

namespace statmc::layers {

/// Whether `buf` holds its pixels in local memory as float (what the views need).
bool has_local_float_pixels(const OIIO::ImageBuf& buf);

/// `src` itself when it already holds local float pixels, else a float copy made in
/// `scratch` (ImageCache-backed or half/uint images). Throws LayerError when the copy
/// fails.
const OIIO::ImageBuf& local_float_pixels(const OIIO::ImageBuf& src, OIIO::ImageBuf& scratch);

/// Channel `channel` of `buf` as a plane whose (0, 0) is the data window's corner
/// (spec.x, spec.y). `buf` must hold local float pixels (throws LayerError otherwise).
ConstPlane channel_plane(const OIIO::ImageBuf& buf, int channel);
Plane channel_plane(OIIO::ImageBuf& buf, int channel);

}  // namespace statmc::layers
