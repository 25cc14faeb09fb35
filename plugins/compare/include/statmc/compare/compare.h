// The compare operator in the style of OIIO's ImageBufAlgo: how far an image is from a
// reference, in the metrics denoising papers report.
#pragma once

#include <optional>

#include <OpenImageIO/imagebuf.h>

#include "statmc/display/display.h"

namespace statmc {

struct CompareMetrics {
    double rmse = 0;    ///< sqrt(mean (x − ref)²)
    double mae = 0;     ///< mean |x − ref|
    double relmse = 0;  ///< mean (x − ref)² / (ref² + ε) (Rousselle et al. 2011)
    double ssim = 1;    ///< mean SSIM of the tone-mapped luminance (Wang et al. 2004)
    double dssim = 0;   ///< (1 − SSIM) / 2
};

struct CompareOptions {
    double relmse_epsilon = 0.01;  ///< ε of relMSE, > 0
    /// The display transform SSIM sees the images through (display.h); without one, the
    /// plain sRGB encoding.
    std::optional<DisplayOptions> display;
};

/// Compares the beauty (R,G,B by name) of `image` with that of `reference`; every mean
/// is over pixels and the three channels. RMSE, MAE and relMSE are on the scene-linear
/// values; SSIM is on the luminance of the LDR images (`options.display` or the sRGB
/// encoding, then clamped to [0, 1]), with
/// an 11×11 Gaussian window (σ = 1.5, truncated and renormalized at the borders), K1 =
/// 0.01, K2 = 0.03, L = 1.
///
/// `error` becomes the per-pixel |image − reference| (R,G,B, float), with the image's
/// data window. The two must share resolution and data window.
///
/// Returns false after `error.errorfmt(...)` naming the problem; never throws.
bool compare(CompareMetrics& metrics, OIIO::ImageBuf& error, const OIIO::ImageBuf& image,
             const OIIO::ImageBuf& reference, const CompareOptions& options = {}, int nthreads = 0);

}  // namespace statmc
