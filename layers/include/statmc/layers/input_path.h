// What every reader asks of a path before it opens it: a regular file. A directory, a
// device (/dev/zero, /dev/urandom) or a pipe would make a reader fail obscurely, read
// without end, or wait for ever.
#pragma once

#include <string>

namespace statmc::layers {

/// "" when `path` is a regular file (after symlinks), else why not: "no such file",
/// "is a directory, not a file", "is not a regular file (a device, pipe or socket)".
std::string input_path_problem(const std::string& path);

}  // namespace statmc::layers
