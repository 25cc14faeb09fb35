// The oidn operator: Intel Open Image Denoise on a statistics image's beauty, in process
// through OIDN's C API, loaded at run time (an optional dependency: the library of the
// `pyoidn` wheel, or a system install). Its output is a candidate for --verify
// (docs/method.md §15), which holds it to the pixels' own statistics.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace statmc {

struct OidnOptions {
    /// Feed OIDN the albedo and normal layers when the image has them (its "RT" filter
    /// with auxiliary images); false: the colour alone.
    bool guides = true;
    /// The OIDN library to load; "" searches (oidn_library_search_text()).
    std::string library;
};

/// `dst` becomes a float copy of `src` whose beauty (R,G,B, or the beauty a renderer's
/// preset names) is OIDN's denoised colour, in HDR mode; every other channel is kept and
/// statmc:denoised is set to 1. The whole data window is denoised (OIDN sees the image
/// whole); `nthreads` > 0 limits OIDN's threads. Returns false after `dst.errorfmt(...)`
/// when the library cannot be loaded (saying how to get it), the beauty holds NaN or Inf
/// (naming the pixel), or OIDN reports an error; never throws.
bool oidn_denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const OidnOptions& opt = {},
                  int nthreads = 0);

/// The return-value form: check `has_error()` on the result.
OIIO::ImageBuf oidn_denoise(const OIIO::ImageBuf& src, const OidnOptions& opt = {},
                            int nthreads = 0);

/// Where the library is looked for, in order, for messages and --help.
std::string oidn_library_search_text();

}  // namespace statmc
