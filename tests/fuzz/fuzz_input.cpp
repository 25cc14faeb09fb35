#include "fuzz_input.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include <unistd.h>

namespace statmc::fuzz {

namespace fs = std::filesystem;

namespace {

std::string scratch_directory()
{
    std::error_code ec;
    if (fs::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0)
        return "/dev/shm";
    const char* tmp = std::getenv("TMPDIR");
    return tmp && *tmp ? tmp : "/tmp";
}

// One file per extension, removed when the process ends normally (a crash leaves it for
// the reproducer; libFuzzer keeps the input itself as the artifact).
struct ScratchFiles {
    std::map<std::string, std::string> paths;
    ~ScratchFiles()
    {
        for (const auto& entry : paths)
            std::remove(entry.second.c_str());
    }
};

}  // namespace

std::vector<std::string> as_lines(const std::uint8_t* data, std::size_t size)
{
    std::vector<std::string> lines;
    std::string line;
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == '\n') {
            lines.push_back(line);
            line.clear();
        } else {
            line.push_back(char(data[i]));
        }
    }
    if (!line.empty())
        lines.push_back(line);
    return lines;
}

const std::string& as_file(const std::uint8_t* data, std::size_t size,
                           const std::string& extension)
{
    static ScratchFiles files;
    std::string& path = files.paths[extension];
    if (path.empty())
        path = scratch_directory() + "/statmc-fuzz-" + std::to_string(getpid()) + extension;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    if (!out.flush())
        throw std::runtime_error("fuzz harness: cannot write " + path);
    return path;
}

}  // namespace statmc::fuzz
