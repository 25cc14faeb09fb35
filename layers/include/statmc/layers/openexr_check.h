// Input files are checked before their pixels are read (docs/reliability.md): their headers
// as bytes, a memory budget on what a header declares, and, where the isolated decoder
// (isolated_decode.h) cannot run, OpenEXR's own fuzz-hardened checker on the whole file, so
// that a damaged or hostile file ends in a clear error naming it, never in a crash, a hang
// or an allocation of the declared 100 GB.
#pragma once

#include <cstdint>
#include <string>

#include <OpenImageIO/imageio.h>

namespace statmc::layers {

/// Whether `path` starts with OpenEXR's magic number.
bool is_openexr_file(const std::string& path);

/// Runs Imf::checkOpenEXRFile (reduced memory and time) on an OpenEXR file. Throws
/// FileError "<path>: damaged OpenEXR file: ..." when it finds the file unreadable.
void check_openexr_structure(const std::string& path);

/// Walks the headers of an OpenEXR file (they are small: no pixel is read), before any
/// library parses them, for what OpenEXR's own reader mishandles: an attribute that
/// declares more bytes than the file holds (OpenEXR 3.1 allocates them first), and a
/// channel listed twice in one part (it silently keeps one). Throws FileError
/// "<path>: damaged OpenEXR file: ...".
void check_openexr_headers(const std::string& path);

/// Half of this machine's physical memory: the default budget of one input image.
std::uint64_t default_read_budget();

/// Throws FileError naming the file, subimage, size and the limit when the pixels `spec`
/// declares would take more than `max_bytes` as float (`--max-memory` sets it), or when
/// its tiles are larger than both 4 times the image and 8192 x 8192 pixels.
void check_read_budget(const std::string& path, int subimage, const OIIO::ImageSpec& spec,
                       std::uint64_t max_bytes);

}  // namespace statmc::layers
