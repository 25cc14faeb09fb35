#include "statmc/layers/openexr_check.h"

#include <cstdio>
#include <fstream>

#include <unistd.h>

#include <OpenEXR/ImfCheckFile.h>

#include "statmc/layers/file_error.h"

namespace statmc::layers {

bool is_openexr_file(const std::string& path)
{
    unsigned char magic[4] = {};
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(magic), 4);
    return in && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

void check_openexr_structure(const std::string& path)
{
    // Reduced memory: the checker skips reads it knows to be huge (the budget below judges
    // those); reduced time: it stops at the first error. It returns true on a bad file.
    if (Imf::checkOpenEXRFile(path.c_str(), /*reduceMemory=*/true, /*reduceTime=*/true))
        throw FileError(path + ": damaged OpenEXR file: OpenEXR's file check fails on it "
                               "(truncated, or corrupted headers, offsets or pixel data)");
}

std::uint64_t default_read_budget()
{
    return std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE)) / 2;
}

namespace {

// "49.2 KB", "181 MB", "120 GB": three digits and a decimal unit.
std::string size_text(double bytes)
{
    static const char* units[] = {"bytes", "KB", "MB", "GB", "TB", "PB"};
    int u = 0;
    while (bytes >= 1000 && u < 5) {
        bytes /= 1000;
        ++u;
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.3g %s", bytes, units[u]);
    return text;
}

}  // namespace

void check_read_budget(const std::string& path, int subimage, const OIIO::ImageSpec& spec,
                       std::uint64_t max_bytes)
{
    // In double: width × height × channels of a hostile header overflows 64 bits.
    const double bytes = double(spec.width) * double(spec.height) * double(spec.depth) *
                         double(spec.nchannels) * sizeof(float);
    if (spec.width < 0 || spec.height < 0 || spec.nchannels < 0 || bytes > double(max_bytes)) {
        throw FileError(path + ": subimage " + std::to_string(subimage) + " declares " +
                        std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        " pixels x " + std::to_string(spec.nchannels) + " channels, " +
                        size_text(bytes) + " as float, more than the " +
                        size_text(double(max_bytes)) + " one image may take (--max-memory)");
    }
}

}  // namespace statmc::layers
