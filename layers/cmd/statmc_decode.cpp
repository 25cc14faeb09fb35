// statmc-decode: OpenEXR's decoder in a process of its own (layers/isolated_decode.h,
// decode_protocol.h). statmc's hosts start it to read a file; it is not a command for
// users. It links OpenEXR alone, so that starting it costs milliseconds.
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledInputPart.h>

#include "statmc/layers/decode_protocol.h"

namespace protocol = statmc::layers::decode_protocol;

namespace {

struct Level {
    int subimage = 0, miplevel = 0, width = 0, height = 0, x = 0, y = 0;
    std::vector<std::string> channels;
};

char* g_message = nullptr;

[[noreturn]] void fail(const std::string& why)
{
    std::strncpy(g_message, why.c_str(), protocol::kMessageBytes - 1);
    std::_Exit(protocol::kDecodeFailed);
}

// Test hooks (tests/layers): a decoder that crashes or hangs, as a damaged file could
// make it.
void injected_fault()
{
    const char* fault = std::getenv("STATMC_DECODE_FAULT");
    if (fault && std::strcmp(fault, "crash") == 0)
        std::raise(SIGSEGV);
    if (fault && std::strcmp(fault, "hang") == 0)
        for (;;)
            ::pause();
}

bool parse_levels(int argc, char** argv, std::vector<Level>& levels)
{
    for (int a = 4; a < argc;) {
        if (argc - a < protocol::kLevelFields)
            return false;
        Level level;
        int* fields[] = {&level.subimage, &level.miplevel, &level.width,
                         &level.height,   &level.x,        &level.y};
        for (int* field : fields)
            *field = std::atoi(argv[a++]);
        const int channels = std::atoi(argv[a++]);
        if (level.width <= 0 || level.height <= 0 || channels <= 0 || argc - a < channels)
            return false;
        level.channels.assign(argv + a, argv + a + channels);
        a += channels;
        levels.push_back(std::move(level));
    }
    return !levels.empty();
}

std::string where(const Level& level)
{
    return "subimage " + std::to_string(level.subimage) + " level " +
           std::to_string(level.miplevel);
}

void check_window(const Level& level, const Imath::Box2i& window)
{
    if (window.min.x != level.x || window.min.y != level.y ||
        window.max.x - window.min.x + 1 != level.width ||
        window.max.y - window.min.y + 1 != level.height)
        fail(where(level) + ": its data window is not the one its header declared");
}

// The level's channels as slices of `pixels` over its data window: float, or a UINT
// channel's bits as stored (the parent converts them as OIIO does).
Imf::FrameBuffer frame_buffer(const Imf::Header& header, const Level& level, char* pixels)
{
    const std::size_t xstride = level.channels.size() * sizeof(float);
    const std::size_t ystride = std::size_t(level.width) * xstride;
    // OpenEXR addresses pixels from the window's origin, which may lie outside the buffer.
    const std::intptr_t origin = reinterpret_cast<std::intptr_t>(pixels) -
                                 std::intptr_t(level.x) * std::intptr_t(xstride) -
                                 std::intptr_t(level.y) * std::intptr_t(ystride);
    Imf::FrameBuffer buffer;
    for (std::size_t c = 0; c < level.channels.size(); ++c) {
        const Imf::Channel* channel = header.channels().findChannel(level.channels[c]);
        if (!channel)
            fail(where(level) + ": no channel '" + level.channels[c] + "'");
        if (channel->xSampling != 1 || channel->ySampling != 1)
            fail(where(level) + ": channel '" + level.channels[c] + "' is subsampled");
        const Imf::PixelType type = channel->type == Imf::UINT ? Imf::UINT : Imf::FLOAT;
        buffer.insert(level.channels[c],
                      Imf::Slice(type, reinterpret_cast<char*>(origin + std::intptr_t(c * 4)),
                                 xstride, ystride));
    }
    return buffer;
}

void decode(Imf::MultiPartInputFile& file, const Level& level, char* pixels)
{
    if (level.subimage >= file.parts())
        fail(where(level) + ": the file has " + std::to_string(file.parts()) + " parts");
    const Imf::Header& header = file.header(level.subimage);
    const Imf::FrameBuffer buffer = frame_buffer(header, level, pixels);
    if (header.type() == Imf::TILEDIMAGE) {
        Imf::TiledInputPart part(file, level.subimage);
        const int l = level.miplevel;
        if (!part.isValidLevel(l, l))
            fail(where(level) + ": no such level");
        check_window(level, part.dataWindowForLevel(l, l));
        part.setFrameBuffer(buffer);
        part.readTiles(0, part.numXTiles(l) - 1, 0, part.numYTiles(l) - 1, l, l);
    } else if (header.type() == Imf::SCANLINEIMAGE && level.miplevel == 0) {
        Imf::InputPart part(file, level.subimage);
        check_window(level, header.dataWindow());
        part.setFrameBuffer(buffer);
        part.readPixels(header.dataWindow().min.y, header.dataWindow().max.y);
    } else {
        fail(where(level) + ": not a flat scanline or tiled image");
    }
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 5)
        return 64;  // run by statmc's hosts only; nothing to tell a user
    // Never outlive the parent. It waits for this process, so the thread that started it
    // lives as long as this process does.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != pid_t(std::atoll(argv[2])))
        return 65;
    const int fd = std::atoi(argv[1]);
    const char* path = argv[3];
    std::vector<Level> levels;
    if (!parse_levels(argc, argv, levels))
        return 66;
    std::vector<std::uint64_t> sizes;
    for (const Level& level : levels)
        sizes.push_back(protocol::level_bytes(level.width, level.height, level.channels.size()));
    const std::vector<std::uint64_t> offsets = protocol::level_offsets(sizes);
    const std::uint64_t total = offsets.back() + protocol::kMessageBytes;
    struct stat st {};
    if (::fstat(fd, &st) != 0 || std::uint64_t(st.st_size) != total)
        return 67;
    void* mapped = ::mmap(nullptr, total, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (mapped == MAP_FAILED)
        return 68;
    char* memory = static_cast<char*>(mapped);
    g_message = memory + offsets.back();
    injected_fault();
    try {
        Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
        Imf::MultiPartInputFile file(path);
        for (std::size_t i = 0; i < levels.size(); ++i)
            decode(file, levels[i], memory + offsets[i]);
    } catch (const std::exception& e) {
        fail(e.what());
    }
    return 0;
}
