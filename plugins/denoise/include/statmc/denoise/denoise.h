// The denoise operator in the style of OIIO's ImageBufAlgo: an image holding per-pixel
// statistics (docs/exr-layers.md) in, the same image with its mean denoised out.
#pragma once

#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/filter.h"
#include "statmc/denoise/denoise_image_options.h"

namespace statmc {

/// Denoises the mean of `opt.aov` (R,G,B of the beauty by default) of `src` with the
/// StatMC filter (docs/method.md §5).
///
/// `dst` becomes a float copy of `src`, every channel and attribute kept, in which the
/// mean channels inside `roi` are replaced by the filtered values and `statmc:denoised` is
/// set to 1. Pixels outside `roi` keep their input values, but the filter still reads
/// neighbours within `opt.filter.radius` outside it. `roi` defaults to the data window;
/// its channel range is ignored (the mean channels are always the ones filtered).
///
/// The test domain follows `opt.test`: Box-Cox when the image has the Box-Cox layers,
/// else the untransformed mean with `variance.*` (statmc:variance says whether that is
/// per sample or of the mean). The image's statistics are checked first (see
/// layers::validate_statistics): a count below 1, a negative variance, and, with
/// NonfinitePolicy::Error, NaN or Inf, refuse the image.
///
/// `dst` may be `src`: the means are then patched in place and the image is not copied
/// (a copy is the size of the whole statistics image). nthreads: 0 uses OIIO's global
/// "threads" attribute, 1 the calling thread only; the result is bitwise the same for any
/// thread count and either form.
///
/// Returns false after `dst.errorfmt(...)` on any error (a missing layer or guide, bad
/// options or statistics); never throws.
bool denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const DenoiseImageOptions& opt,
             OIIO::ROI roi = {}, int nthreads = 0);

/// The return-value form: check `has_error()` on the result.
OIIO::ImageBuf denoise(const OIIO::ImageBuf& src, const DenoiseImageOptions& opt,
                       OIIO::ROI roi = {}, int nthreads = 0);

/// The same over the pixels of `roi` where `where` is non-zero (PixelMask: one byte per
/// pixel of `src`'s data window, row-major; empty: every pixel). Those come out bitwise as
/// in the full denoise; every other pixel keeps its input values, as outside `roi`. The
/// filter skips what no wanted pixel needs; the image's preparation (estimators, variances)
/// is still whole. verify's fallback runs it on the pixels it rejects.
bool denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const PixelMask& where,
             const DenoiseImageOptions& opt, OIIO::ROI roi = {}, int nthreads = 0);

/// The frames around `src` in a sequence, nearest first: previous[0] is frame t − 1,
/// next[0] frame t + 1. At a sequence's ends one side is shorter or empty.
struct FrameNeighbours {
    std::vector<const OIIO::ImageBuf*> previous;
    std::vector<const OIIO::ImageBuf*> next;
};

/// Temporal denoising (docs/method.md §13): the same, but first the members that the
/// nearest `opt.temporal.frames` frames on each side offer are merged into `src`'s
/// statistics (core/temporal_merge.h), following the motion layer (motion.X/Y) when
/// every frame has it. Fewer neighbours than asked for (a sequence's ends) use those
/// given. Every neighbour must be the same frame (resolution, data window) with every
/// statistic that `src` is denoised from; a motion layer in only some frames is an error.
/// `dst` keeps `src`'s own statistics: only the mean is replaced. With
/// opt.temporal.frames = 0 or no neighbours it is the single-frame denoise.
bool denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
             const DenoiseImageOptions& opt, OIIO::ROI roi = {}, int nthreads = 0);
OIIO::ImageBuf denoise(const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
                       const DenoiseImageOptions& opt, OIIO::ROI roi = {}, int nthreads = 0);

}  // namespace statmc
