// What the fuzz targets share: the input as text, as arguments, or as a file for the
// readers that take a path (OpenEXR's checker and OIIO open files by name).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace statmc::fuzz {

inline std::string as_text(const std::uint8_t* data, std::size_t size)
{
    return std::string(reinterpret_cast<const char*>(data), size);
}

/// The input split at newlines: one argument per line, as a seed file is written.
std::vector<std::string> as_lines(const std::uint8_t* data, std::size_t size);

/// Writes the input to this process's own file named "statmc-fuzz-<pid><extension>" (in
/// /dev/shm when it is there, else $TMPDIR or /tmp; removed at exit) and returns its path.
const std::string& as_file(const std::uint8_t* data, std::size_t size,
                           const std::string& extension);

}  // namespace statmc::fuzz
