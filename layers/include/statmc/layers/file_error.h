// Reading or writing an image file failed: a message naming the file, fit to show a user.
#pragma once

#include <stdexcept>
#include <string>

namespace statmc::layers {

class FileError : public std::runtime_error {
public:
    explicit FileError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace statmc::layers
