// Image files in and out, for every host (the statmc tool, the renderer). Reads are complete and immediate, so a truncated file fails at
// -i; writes go to a temporary file in the target directory and are renamed into place,
// so a failed write never leaves a partial or stray file.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// Reads subimage 0 of `path` into local float pixels. Throws FileError "<path>: ...".
OIIO::ImageBuf read_image_file(const std::string& path);

/// Writes `image` to `path` as OpenEXR under the layer contract's storage rules (float,
/// scanline, lossless). Throws FileError "<path>: cannot write: ...".
void write_image_file(const OIIO::ImageBuf& image, const std::string& path);

}  // namespace statmc::layers
