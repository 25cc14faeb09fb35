// The verify operator in the style of OIIO's ImageBufAlgo: a statistics image and another
// denoiser's output of the same frame (the candidate) in; out, the candidate wherever the
// pixels' own samples cannot reject it, and statmc's estimate where they can and that
// estimate can too, with a map of where (docs/method.md §15).
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/candidate_test.h"
#include "statmc/denoise/denoise_image_options.h"

namespace statmc {

/// What replaces a rejected candidate pixel.
enum class VerifyFallback {
    Denoise,  ///< the denoise operator's estimate with `VerifyOptions::denoise`
    Mean,     ///< the pixel's own noisy mean: unbiased, and cheaper
};

struct VerifyOptions {
    CandidateTestOptions test;  ///< the level and the box (alpha 0.001, 3×3)
    VerifyFallback fallback = VerifyFallback::Denoise;
    /// The denoise whose estimate a rejected pixel takes (the default method); its `aov`
    /// is the layer verified, its variance moderation (variance_prior_dof and _alpha)
    /// the one the test reads.
    DenoiseImageOptions denoise;
    /// The candidate's layer ("" = its R,G,B, or the beauty a renderer's preset names).
    std::string candidate_layer;
};

/// `dst` becomes a float copy of `src` whose AOV means inside `roi` are the candidate's
/// where it was kept and the fallback's where it was rejected, with one channel more,
/// `diagnostics.rejected` (layers::diagnostics_channel): 0 where kept, else the
/// CandidateRejection bits (1: by the pixel, 2: by its box, 3: both). The header records
/// statmc:denoised = 1 and statmc:verifyRejected (the rejected share of the roi's pixels).
///
/// With VerifyFallback::Denoise a pixel the samples reject is tested again with the
/// denoise's estimate in place of its mean, and replaced only where that rejects it too.
///
/// `src` needs the AOV's variance and sample count (docs/exr-layers.md; a renderer's
/// preset maps them); `candidate` the same data window and a three-channel layer, finite
/// inside `roi`. The fallback's denoise computes the rejected pixels and their boxes (a
/// masked denoise, bitwise the full one's values there; none when nothing is rejected).
/// Bitwise the same for any `nthreads` (0 = OIIO's "threads").
///
/// Returns false after `dst.errorfmt(...)` naming the image, layer or pixel; never throws.
bool verify(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const OIIO::ImageBuf& candidate,
            const VerifyOptions& opt, OIIO::ROI roi = {}, int nthreads = 0);

/// The return-value form: check `has_error()` on the result.
OIIO::ImageBuf verify(const OIIO::ImageBuf& src, const OIIO::ImageBuf& candidate,
                      const VerifyOptions& opt, OIIO::ROI roi = {}, int nthreads = 0);

}  // namespace statmc
