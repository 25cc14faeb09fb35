#include "statmc/layers/input_path.h"

#include <filesystem>
#include <system_error>

namespace statmc::layers {

std::string input_path_problem(const std::string& path)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found)
        return "no such file";
    if (ec)
        return ec.message();
    if (status.type() == std::filesystem::file_type::directory)
        return "is a directory, not a file";
    if (status.type() != std::filesystem::file_type::regular)
        return "is not a regular file (a device, pipe or socket)";
    return {};
}

}  // namespace statmc::layers
