// The display operator in the style of OIIO's ImageBufAlgo: scene-linear R,G,B to a
// display's encoding through an OpenColorIO (2.1) display/view.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace statmc {

struct DisplayOptions {
    std::string config;   ///< an OCIO config file; "" uses $OCIO
    std::string display;  ///< "" is the config's default display
    std::string view;     ///< "" is the display's default view
};

/// The config to use: `given` when not empty, else $OCIO when set, else the config that
/// ships with statmc, `display/config.ocio` in the directory of `module` (the plugin file).
std::string display_config(const std::string& given, const std::string& module);

/// Applies the config's scene_linear → (display, view) transform to R,G,B of `src`
/// (found by name). `dst` is a float R,G,B image (plus A, untouched, when `src` has one)
/// with `src`'s data window; metadata is kept, `oiio:ColorSpace` set to the view.
///
/// Returns false after `dst.errorfmt(...)` for a config that cannot be read (naming the
/// file), a display or view the config lacks (naming it and listing the available ones),
/// or an image without R,G,B; never throws.
bool display(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const DisplayOptions& options,
             int nthreads = 0);

/// The return-value form: check `has_error()` on the result.
OIIO::ImageBuf display(const OIIO::ImageBuf& src, const DisplayOptions& options, int nthreads = 0);

}  // namespace statmc
