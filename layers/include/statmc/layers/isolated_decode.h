// OpenEXR's decoder run in a child process (docs/reliability.md, step 4): the file's pixels
// are decoded once, by the decoder program statmc-decode (layers/cmd/statmc_decode.cpp),
// into shared memory sized from headers the parent has already judged, so that a crash or
// a hang of the decoder on a damaged file ends in a clear error naming the file, never in
// the death of the host (the statmc tool, the Python module, a renderer) or a hang.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// One MIP level of one subimage, as the header declares it.
struct DecodeLevel {
    int subimage = 0;
    int miplevel = 0;
    OIIO::ImageSpec spec;  ///< the header's; depth 1, within the read budget
};

/// The decoder program, or empty when none ships with this program (then a host checks
/// the file with OpenEXR's checker and decodes it itself). $STATMC_DECODER names another.
std::string decoder_program();

/// Decodes `levels` of `path` in the decoder program's process, each into a float ImageBuf
/// named `path` with the header's spec (float, as a forced float read gives it). Nothing
/// (nullopt) where the decoder cannot run here: no decoder ships with the program, or no
/// shared memory of that size can be made. A decoder that fails, dies or runs longer than
/// `timeout_seconds` (0: a minute plus a second per 16 MB of float pixels) throws
/// FileError "<path>: damaged OpenEXR file: ..."; the decoder never outlives the call,
/// nor its parent.
std::optional<std::vector<OIIO::ImageBuf>> decode_isolated(const std::string& path,
                                                           const std::vector<DecodeLevel>& levels,
                                                           double timeout_seconds = 0);

}  // namespace statmc::layers
