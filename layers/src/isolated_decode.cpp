#include "statmc/layers/isolated_decode.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "statmc/layers/decode_protocol.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/shipped_files.h"

extern char** environ;

namespace statmc::layers {

namespace {

namespace protocol = decode_protocol;

std::uint64_t level_bytes(const OIIO::ImageSpec& spec)
{
    return protocol::level_bytes(std::uint64_t(spec.width), std::uint64_t(spec.height),
                                 std::uint64_t(spec.nchannels));
}

[[noreturn]] void fail(const std::string& path, const std::string& why)
{
    throw FileError(path + ": " + why);
}

struct Descriptor {
    int fd = -1;
    ~Descriptor()
    {
        if (fd >= 0)
            ::close(fd);
    }
};

// A spawned decoder that an exception in the parent must not leave running.
struct Child {
    pid_t pid = -1;
    ~Child()
    {
        if (pid > 0) {
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
            }
        }
    }
};

void add_level_arguments(const DecodeLevel& level, std::vector<std::string>& args)
{
    const OIIO::ImageSpec& s = level.spec;
    for (int value : {level.subimage, level.miplevel, s.width, s.height, s.x, s.y, s.nchannels})
        args.push_back(std::to_string(value));
    args.insert(args.end(), s.channelnames.begin(), s.channelnames.end());
}

pid_t spawn_decoder(const std::string& path, const std::vector<DecodeLevel>& levels,
                    const std::string& decoder, int memfd)
{
    std::vector<std::string> args = {decoder, std::to_string(protocol::kChildFd),
                                     std::to_string(::getpid()), path};
    for (const DecodeLevel& level : levels)
        add_level_arguments(level, args);
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    ::posix_spawn_file_actions_init(&actions);
    ::posix_spawnattr_init(&attributes);
    // The memory as descriptor 3 (dup2 clears close-on-exec), and the decoding libraries'
    // own messages kept out of the host's output: the parent reports the failure.
    ::posix_spawn_file_actions_adddup2(&actions, memfd, protocol::kChildFd);
    ::posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    ::posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    // Nothing else of the host's (its outputs' temporaries, a Python session's files).
    ::posix_spawn_file_actions_addclosefrom_np(&actions, protocol::kChildFd + 1);
    // Default signal actions and no blocked signal, whatever the host set (Python catches
    // SIGINT): an interrupt from the terminal ends the decoder with its parent.
    sigset_t all, none;
    sigfillset(&all);
    sigemptyset(&none);
    ::posix_spawnattr_setsigdefault(&attributes, &all);
    ::posix_spawnattr_setsigmask(&attributes, &none);
    ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    pid_t pid = -1;
    const int error =
        ::posix_spawn(&pid, decoder.c_str(), &actions, &attributes, argv.data(), environ);
    ::posix_spawn_file_actions_destroy(&actions);
    ::posix_spawnattr_destroy(&attributes);
    if (error != 0)
        fail(path, "cannot start the decoder " + decoder + ": " + std::strerror(error));
    return pid;
}

// The decoder's exit status. One that outlives `timeout_seconds` is named in the error,
// and Child's destructor stops it on the way out.
int wait_for(Child& child, const std::string& path, double timeout_seconds)
{
    using Clock = std::chrono::steady_clock;
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_seconds);
    auto pause = std::chrono::microseconds(200);
    int status = 0;
    for (;;) {
        const pid_t done = ::waitpid(child.pid, &status, WNOHANG);
        if (done == child.pid)
            break;
        if (done < 0 && errno != EINTR)
            fail(path, std::string("lost the decoder: ") + std::strerror(errno));
        if (Clock::now() > deadline)
            fail(path, "damaged OpenEXR file: the decoder did not finish in " +
                           std::to_string(int(timeout_seconds)) + " s and was stopped");
        std::this_thread::sleep_for(pause);
        pause = std::min(pause * 2, std::chrono::microseconds(10000));
    }
    child.pid = -1;
    return status;
}

std::string read_message(int memfd, std::uint64_t at)
{
    char text[protocol::kMessageBytes] = {};
    if (::pread(memfd, text, protocol::kMessageBytes - 1, off_t(at)) < 0)
        return "(its message could not be read)";
    return text;
}

// The decoder leaves a UINT channel's bits as stored; OIIO's float read scales them to
// [0, 1], and so does this, with OIIO's own conversion.
void convert_uint_channels(const OIIO::ImageSpec& file_spec, OIIO::ImageBuf& image)
{
    const std::size_t pixels = std::size_t(file_spec.width) * std::size_t(file_spec.height);
    float* data = static_cast<float*>(image.localpixels());
    for (int c = 0; c < file_spec.nchannels; ++c) {
        if (file_spec.channelformat(c) != OIIO::TypeDesc::UINT)
            continue;
        for (std::size_t p = 0; p < pixels; ++p) {
            float* value = data + p * std::size_t(file_spec.nchannels) + std::size_t(c);
            std::uint32_t bits;
            std::memcpy(&bits, value, sizeof bits);
            OIIO::convert_pixel_values(OIIO::TypeDesc::UINT, &bits, OIIO::TypeDesc::FLOAT, value);
        }
    }
}

// Level `level` out of the memory into a float ImageBuf, freeing the memory's pages as it
// goes so that the copy never holds the pixels twice over.
OIIO::ImageBuf copy_out(const std::string& path, const DecodeLevel& level, int memfd,
                        std::uint64_t offset)
{
    OIIO::ImageSpec spec = level.spec;
    spec.set_format(OIIO::TypeDesc::FLOAT);
    spec.channelformats.clear();
    OIIO::ImageBuf image(path, spec, OIIO::InitializePixels::No);
    char* pixels = static_cast<char*>(image.localpixels());
    const std::uint64_t bytes = level_bytes(level.spec);
    constexpr std::uint64_t kChunk = 16u << 20;  // a multiple of the page
    for (std::uint64_t done = 0; done < bytes;) {
        const std::uint64_t n = std::min(kChunk, bytes - done);
        const ssize_t got = ::pread(memfd, pixels + done, n, off_t(offset + done));
        if (got <= 0)
            fail(path, std::string("cannot read the decoded pixels: ") +
                           (got < 0 ? std::strerror(errno) : "short read"));
        ::fallocate(memfd, FALLOC_FL_PUNCH_HOLE | FALLOC_FL_KEEP_SIZE, off_t(offset + done),
                    off_t(protocol::page_up(std::uint64_t(got))));
        done += std::uint64_t(got);
    }
    convert_uint_channels(level.spec, image);
    return image;
}

double automatic_timeout(std::uint64_t bytes) { return 60.0 + double(bytes) / double(16u << 20); }

}  // namespace

std::string decoder_program()
{
    if (const char* named = std::getenv("STATMC_DECODER"))
        return named;
#ifdef STATMC_BUILD_DECODER
    const std::vector<std::string> found = shipped_paths("statmc-decode", STATMC_BUILD_DECODER);
#else
    const std::vector<std::string> found = shipped_paths("statmc-decode");
#endif
    return found.empty() ? std::string() : found.front();
}

std::optional<std::vector<OIIO::ImageBuf>> decode_isolated(const std::string& path,
                                                           const std::vector<DecodeLevel>& levels,
                                                           double timeout_seconds)
{
    const std::string decoder = decoder_program();
    if (decoder.empty())
        return std::nullopt;
    std::vector<std::uint64_t> sizes;
    for (const DecodeLevel& level : levels)
        sizes.push_back(level_bytes(level.spec));
    const std::vector<std::uint64_t> offsets = protocol::level_offsets(sizes);
    const std::uint64_t total = offsets.back() + protocol::kMessageBytes;
    if (timeout_seconds <= 0)
        timeout_seconds = automatic_timeout(total);

    // Shared memory is a file to the kernel: a file size limit (ulimit -f) applies to it.
    if (rlimit limit{}; ::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
                        total > limit.rlim_cur)
        return std::nullopt;
    Descriptor memory{::memfd_create("statmc-decode", MFD_CLOEXEC)};
    if (memory.fd < 0 || ::ftruncate(memory.fd, off_t(total)) != 0)
        return std::nullopt;
    if (memory.fd == protocol::kChildFd) {  // dup2 onto itself would keep close-on-exec
        Descriptor moved{::fcntl(memory.fd, F_DUPFD_CLOEXEC, protocol::kChildFd + 1)};
        std::swap(memory.fd, moved.fd);
    }
    Child child{spawn_decoder(path, levels, decoder, memory.fd)};
    const int status = wait_for(child, path, timeout_seconds);
    if (WIFSIGNALED(status))
        fail(path, std::string("damaged OpenEXR file: the decoder died of ") +
                       ::strsignal(WTERMSIG(status)) + " (signal " +
                       std::to_string(WTERMSIG(status)) + ") while reading it");
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == protocol::kDecodeFailed)
        fail(path, "damaged OpenEXR file: " + read_message(memory.fd, offsets.back()));
    if (code != 0)  // a sanitizer's report, say: a death all the same
        fail(path, "damaged OpenEXR file: the decoder stopped with exit status " +
                       std::to_string(code) + " while reading it (" + decoder + ")");

    std::vector<OIIO::ImageBuf> images;
    for (std::size_t i = 0; i < levels.size(); ++i)
        images.push_back(copy_out(path, levels[i], memory.fd, offsets[i]));
    return images;
}

}  // namespace statmc::layers
