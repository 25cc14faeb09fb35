// The passes operator in the style of OIIO's ImageBufAlgo: K independent renders of one
// frame (different seeds) in, a statistics image (docs/exr-layers.md) out. This is how a
// renderer without statmc integration gets denoised (docs/method.md; core/passes.h).
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc {

/// Treats each render as one sample of every pixel. The beauty (R,G,B, or Y) becomes its
/// statistics: the mean of the renders, `variance.*` = their per-render sample variance
/// (`statmc:variance` = "sample"), `sampleCount.Y` = K; denoising the result tests the
/// untransformed means with df = 2K − 2. Every other channel (alpha, albedo, normal, ...)
/// is carried as its mean over the renders, and the first render's metadata is kept
/// (statmc:spp, statmc:seed and statmc:denoised dropped, as they described one render).
/// A non-finite or negative render pixel counts as 0, as a broken sample would.
///
/// The renders must number at least 2 and share the data window and the set of channel
/// names; they must be plain renders, not statistics images. `dst` covers `roi` (default:
/// the data window) and is float.
///
/// Renders written under another renderer's names (Blender's multilayer
/// `ViewLayer.Combined.R`, `ViewLayer.Denoising Albedo.R`, ...) are read through its preset
/// (options.from, layers/renderer_presets.h): the beauty becomes R,G,B(,A) and the guides
/// albedo, normal and depth, so that the result denoises with them.
///
/// Returns false after `dst.errorfmt(...)` on any error, naming the offending renders by
/// index and ImageBuf name; never throws.
struct PassesOptions {
    /// Whose channel names the renders have: "auto" detects them (docs/renderers.md).
    std::string from = "auto";
};

bool passes(OIIO::ImageBuf& dst, const std::vector<const OIIO::ImageBuf*>& renders,
            const PassesOptions& options, OIIO::ROI roi = {}, int nthreads = 0);
bool passes(OIIO::ImageBuf& dst, const std::vector<const OIIO::ImageBuf*>& renders,
            OIIO::ROI roi = {}, int nthreads = 0);

/// The return-value form: check `has_error()` on the result.
OIIO::ImageBuf passes(const std::vector<const OIIO::ImageBuf*>& renders,
                      const PassesOptions& options, OIIO::ROI roi = {}, int nthreads = 0);
OIIO::ImageBuf passes(const std::vector<const OIIO::ImageBuf*>& renders, OIIO::ROI roi = {},
                      int nthreads = 0);

}  // namespace statmc
