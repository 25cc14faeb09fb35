// What reading a file through the layer contract says: the FileError's text, "" on success.
#pragma once

#include <string>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"

namespace statmc::test {

inline std::string read_error(const std::string& path, const layers::ReadOptions& options = {})
{
    try {
        layers::read_image_file(path, options);
    } catch (const layers::FileError& e) {
        return e.what();
    }
    return "";
}

}  // namespace statmc::test
