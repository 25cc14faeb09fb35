// One run of the denoise pipeline: the statistics of one lead layer found once, the
// method's stages planned, the frames merged, the filter run, the means written.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

#include "statmc/denoise/denoise.h"

namespace statmc::denoising {

/// Denoises `run.aov` (and, with `run.joint`, the AOVs it lists) of `in`, local float
/// pixels under the contract's names, into `out`: `in` itself (in place, ImageBufAlgo's
/// dst == src) or an image that becomes a float copy of `in`. Returns the stages of the
/// method left out, and why ("" when none). `where`: only those pixels of the data window
/// (PixelMask; empty: all). Throws on a missing layer or bad statistics.
std::string denoise_layer(const OIIO::ImageBuf& in, OIIO::ImageBuf& out,
                          const FrameNeighbours& neighbours, const DenoiseImageOptions& run,
                          const OIIO::ROI& roi, const PixelMask& where, int nthreads);

}  // namespace statmc::denoising
