// Image files in and out, for every host (the statmc tool, the renderer). Reads are complete and
// immediate, so a truncated file fails at -i; writes go to a temporary file in the target directory
// and are renamed into place, so a failed write never leaves a partial or stray file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// Turns off OIIO's "OIIO DEBUG:" lines (Debian's build prints them by default, before a
/// host's own error) unless $OPENIMAGEIO_DEBUG asks for them. Hosts call it at start.
void silence_library_debug_messages();

/// What one read may take: a hostile header must not take the machine.
struct ReadOptions {
    /// The most bytes one subimage may take as float pixels; 0: half of physical memory.
    std::uint64_t max_memory = 0;
    /// Guard against OpenEXR's decoder on a damaged file: decode it in the isolated
    /// decoder (isolated_decode.h), or where none ships, check it with OpenEXR's own
    /// checker first (about 3.5 times the read). Off: decode in this process, for files the
    /// pipeline wrote itself (docs/reliability.md).
    bool check_structure = true;
    /// Seconds the isolated decoder may take; 0: a minute plus a second per 16 MB.
    double decode_timeout = 0;
};

/// Reads subimage 0 of `path` into local float pixels, after the header's checks and the
/// memory budget of `options` (openexr_check.h), an EXR through the isolated decoder. Throws
/// FileError
/// "<path>: ...".
OIIO::ImageBuf read_image_file(const std::string& path, const ReadOptions& options = {});

/// The checks read_image_file makes of the headers (subimage 0) and, for an EXR with
/// `check_structure`, OpenEXR's check of the whole file: for a host that decodes the file
/// in its own process another way (a texture through OIIO). Throws FileError "<path>: ...".
void check_image_file(const std::string& path, const ReadOptions& options = {});

/// The header of subimage 0 of `path`, after the checks read_image_file makes of headers
/// (OpenEXR's check of the whole file excepted): what a host compares across the frames
/// of a sequence before reading their pixels. Throws FileError "<path>: ...".
OIIO::ImageSpec read_image_header(const std::string& path, const ReadOptions& options = {});

/// The headers of every subimage of `path` as stored (their pixel types: a float read's
/// ImageBuf may not know them), after the same checks. Throws FileError "<path>: ...".
std::vector<OIIO::ImageSpec> read_image_headers(const std::string& path,
                                                const ReadOptions& options = {});

/// The MIP levels below the full resolution, per subimage (empty for a subimage that has
/// none): what a copy writes back so that a MIP-mapped file stays whole.
using MipLevels = std::vector<std::vector<OIIO::ImageBuf>>;

/// Every subimage (EXR part) of `path`, each as read_image_file reads subimage 0; with
/// `mip_levels`, also each subimage's coarser MIP levels, in float.
std::vector<OIIO::ImageBuf> read_image_subimages(const std::string& path,
                                                 const ReadOptions& options = {},
                                                 MipLevels* mip_levels = nullptr);

/// How a write may depart from the storage rules, when a user asks for it explicitly.
struct WriteOptions {
    OIIO::TypeDesc format = OIIO::TypeDesc::UNKNOWN;  ///< UNKNOWN: float32, the contract's
    std::string compression;                          ///< empty: the contract's rule
};

/// Writes `image` to `path` as OpenEXR under the layer contract's storage rules (float,
/// scanline, lossless); a plain picture without statistics channels (what --display
/// makes) may go to any format OIIO writes, chosen by the extension (PNG, JPEG, TIFF).
/// Throws FileError "<path>: cannot write: ...".
void write_image_file(const OIIO::ImageBuf& image, const std::string& path);

/// Writes `subimages` (at least one) as the parts of one OpenEXR file, atomically as
/// above, with `options` overriding the pixel type and compression. A subimage with
/// `mip_levels` (empty, or one entry per subimage) is written as a tiled MIP map; MIP
/// levels in a file of several subimages are refused (OIIO 2.4 cannot write them).
void write_image_file(const std::vector<OIIO::ImageBuf>& subimages, const std::string& path,
                      const WriteOptions& options, const MipLevels& mip_levels = {});

}  // namespace statmc::layers
