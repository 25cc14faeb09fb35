// Image files in and out, for every host (the statmc tool, the renderer). Reads are complete and
// immediate, so a truncated file fails at -i; writes go to a temporary file in the target directory
// and are renamed into place, so a failed write never leaves a partial or stray file.
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// Reads subimage 0 of `path` into local float pixels. Throws FileError "<path>: ...".
OIIO::ImageBuf read_image_file(const std::string& path);

/// Every subimage (EXR part) of `path`, each as read_image_file reads subimage 0.
std::vector<OIIO::ImageBuf> read_image_subimages(const std::string& path);

/// How a write may depart from the storage rules, when a user asks for it explicitly.
struct WriteOptions {
    OIIO::TypeDesc format = OIIO::TypeDesc::UNKNOWN;  ///< UNKNOWN: float32, the contract's
    std::string compression;                          ///< empty: the contract's rule
};

/// Writes `image` to `path` as OpenEXR under the layer contract's storage rules (float,
/// scanline, lossless). Throws FileError "<path>: cannot write: ...".
void write_image_file(const OIIO::ImageBuf& image, const std::string& path);

/// Writes `subimages` (at least one) as the parts of one OpenEXR file, atomically as
/// above, with `options` overriding the pixel type and compression.
void write_image_file(const std::vector<OIIO::ImageBuf>& subimages, const std::string& path,
                      const WriteOptions& options);

}  // namespace statmc::layers
