#include "statmc/layers/openexr_check.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

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

namespace {

// A reader of the header bytes that stops (fails) at the end of the file or at anything
// longer than OpenEXR allows, so that a damaged header cannot make it loop or allocate.
struct HeaderBytes {
    std::ifstream in;
    std::streamoff file_size;

    std::streamoff remaining() { return file_size - std::streamoff(in.tellg()); }

    bool text(std::string& out)  // a null-terminated name, at most 255 characters
    {
        out.clear();
        for (char c; in.get(c);) {
            if (c == '\0')
                return true;
            if (out.size() == 255)
                return false;
            out.push_back(c);
        }
        return false;
    }
    bool int32(std::int32_t& value)
    {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4))
            return false;
        value = std::int32_t(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 |
                             std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24);
        return true;
    }
    bool skip(std::int32_t bytes) { return bytes >= 0 && bool(in.seekg(bytes, std::ios::cur)); }
};

// The bytes OpenEXR 3.1 reads for a value of a fixed-size type, whatever size the header
// declares (it reads these types by their layout, not by the declared size); 0 for the
// types it reads by the declared size.
int fixed_value_size(const std::string& type)
{
    static const std::map<std::string, int> sizes = {
        {"box2i", 16},  {"box2f", 16},   {"chromaticities", 32}, {"compression", 1},
        {"double", 8},  {"envmap", 1},   {"float", 4},           {"int", 4},
        {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36},         {"m33d", 72},
        {"m44f", 64},   {"m44d", 128},   {"rational", 8},        {"tiledesc", 9},
        {"timecode", 8}, {"v2i", 8},     {"v2f", 8},             {"v2d", 16},
        {"v3i", 12},    {"v3f", 12},     {"v3d", 24},            {"deepImageState", 1}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

// Whether each string of a stringvector value (length, then bytes) fits in its declared
// `size`: OpenEXR allocates each length before reading it. Leaves the stream where it was.
bool strings_fit(HeaderBytes& bytes, std::int32_t size)
{
    const std::streamoff start = bytes.in.tellg();
    std::int64_t read = 0;
    bool fit = true;
    while (read < size) {
        std::int32_t length = 0;
        if (!bytes.int32(length) || length < 0 || length > size - read - 4) {
            fit = false;
            break;
        }
        read += 4 + length;
        bytes.skip(length);
    }
    bytes.in.clear();
    bytes.in.seekg(start);
    return fit;
}

// A chlist value, read as OpenEXR reads it (entries up to an empty name, whatever size
// was declared): the channel named twice, or "".
std::string repeated_channel(HeaderBytes& bytes)
{
    std::set<std::string> names;
    std::string name;
    while (bytes.text(name) && !name.empty()) {
        if (!names.insert(name).second)
            return name;
        if (!bytes.skip(16))  // pixel type, pLinear + reserved, x and y sampling
            break;
    }
    return {};
}

}  // namespace

void check_openexr_headers(const std::string& path)
{
    std::error_code ec;
    const auto file_size = std::filesystem::file_size(path, ec);
    if (ec)
        return;  // the reader reports it
    HeaderBytes bytes{std::ifstream(path, std::ios::binary), std::streamoff(file_size)};
    std::int32_t magic = 0, version = 0;
    if (!bytes.int32(magic) || !bytes.int32(version))
        return;  // too short: the reader says so
    const bool multipart = version & 0x1000;
    std::string name, type;
    // Attributes until an empty name ends a header; a multi-part file's headers until an
    // empty header ends the list. Each step consumes bytes, so the end of the file ends it.
    for (int part = 0;; ++part) {
        if (!bytes.text(name) || name.empty())
            return;
        do {
            std::int32_t size = 0;
            if (!bytes.text(type) || !bytes.int32(size) || size < 0)
                return;
            // OpenEXR 3.1 allocates what a string, vector, preview or unknown attribute
            // declares before it reads it: a 700-byte file may ask for gigabytes.
            auto refuse_size = [&](double declared) {
                throw FileError(path + ": damaged OpenEXR file: attribute '" + name + "' of part " +
                                std::to_string(part) + " declares " +
                                std::to_string(std::int64_t(declared)) +
                                " bytes, more than the rest of the file holds");
            };
            // Walk as OpenEXR reads, so that the next attribute is the one it sees.
            if (const int fixed = fixed_value_size(type); fixed > 0) {
                if (!bytes.skip(fixed))
                    return;
            } else if (type == "chlist") {
                const std::string twice = repeated_channel(bytes);
                if (!twice.empty())
                    throw FileError(path + ": damaged OpenEXR file: part " + std::to_string(part) +
                                    " lists channel '" + twice + "' twice (a reader would "
                                    "silently keep only one of them)");
            } else if (type == "preview") {
                std::int32_t width = 0, height = 0;
                if (!bytes.int32(width) || !bytes.int32(height))
                    return;
                const double pixels = 4.0 * double(std::uint32_t(width)) * double(std::uint32_t(height));
                if (pixels > double(bytes.remaining()))
                    refuse_size(pixels);
                if (!bytes.skip(std::int32_t(pixels)))
                    return;
            } else {
                if (size > bytes.remaining())
                    refuse_size(size);
                if (type == "stringvector" && !strings_fit(bytes, size))
                    refuse_size(size);
                if (!bytes.skip(size))
                    return;
            }
        } while (bytes.text(name) && !name.empty());
        if (!multipart)
            return;
    }
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
    // A reader allocates a whole tile at once: a tile of 16 x 20 000 000 pixels on a 32 x 32
    // image (found by the fuzzer) took 3.9 GB. Tiles larger than the image are legal (64 x 64
    // on 32 x 32), so only those larger than both 4 times the image and 8192 x 8192 are
    // refused.
    const double tile_pixels =
        double(spec.tile_width) * double(spec.tile_height) * double(std::max(spec.tile_depth, 1));
    if (spec.tile_width > 0 &&
        tile_pixels > std::max(4.0 * double(spec.width) * double(spec.height), 8192.0 * 8192.0))
        throw FileError(path + ": subimage " + std::to_string(subimage) + " declares tiles of " +
                        std::to_string(spec.tile_width) + "x" + std::to_string(spec.tile_height) +
                        " pixels for a " + std::to_string(spec.width) + "x" +
                        std::to_string(spec.height) +
                        " image, far larger than the image (a damaged header?)");
    if (spec.width < 0 || spec.height < 0 || spec.nchannels < 0 || bytes > double(max_bytes)) {
        throw FileError(path + ": subimage " + std::to_string(subimage) + " declares " +
                        std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        " pixels x " + std::to_string(spec.nchannels) + " channels, " +
                        size_text(bytes) + " as float, more than the " +
                        size_text(double(max_bytes)) + " one image may take (--max-memory)");
    }
}

}  // namespace statmc::layers
