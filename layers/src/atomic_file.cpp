#include "statmc/layers/atomic_file.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "statmc/layers/file_error.h"

namespace statmc::layers {

namespace fs = std::filesystem;

namespace {

// The temporaries being written, where a signal handler can find them: fixed storage and
// lock-free flags, since a handler may neither allocate nor lock. A write that finds the
// table full (more than 64 at once) is not listed; the next write of its target still
// removes what it leaves. A slot is marked listed only after its path is complete; a
// handler running while another thread reuses a slot could read a half-copied name and
// unlink nothing (hosts write one file at a time, so this stays theoretical).
struct PendingSlot {
    std::atomic<bool> taken{false};
    std::atomic<bool> listed{false};
    char path[PATH_MAX] = {};
};
std::array<PendingSlot, 64> g_pending;

PendingSlot* list_pending(const std::string& path)
{
    if (path.size() >= PATH_MAX)
        return nullptr;
    for (PendingSlot& slot : g_pending) {
        bool expected = false;
        if (slot.taken.compare_exchange_strong(expected, true)) {
            std::memcpy(slot.path, path.c_str(), path.size() + 1);
            slot.listed.store(true);
            return &slot;
        }
    }
    return nullptr;
}

void unlist_pending(PendingSlot* slot)
{
    if (!slot)
        return;
    slot->listed.store(false);
    slot->taken.store(false);
}

// Removes the temporary file unless the write got as far as renaming it; listed while it
// exists, so that a signal removes it too.
class TemporaryFile {
public:
    explicit TemporaryFile(fs::path path) : path_(std::move(path)), slot_(list_pending(path_))
    {
    }
    ~TemporaryFile()
    {
        if (!path_.empty()) {
            std::error_code ignored;
            fs::remove(path_, ignored);
        }
        unlist_pending(slot_);
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    const fs::path& path() const { return path_; }
    void release() { path_.clear(); }

private:
    fs::path path_;
    PendingSlot* slot_;
};

[[noreturn]] void cannot_write(const std::string& path, const std::string& why)
{
    throw FileError(path + ": cannot write: " + why);
}

fs::path directory_of(const fs::path& target)
{
    return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

std::string host_name()
{
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    return name;
}

// ".out.exr.statmc-tmp-<host>-": what every temporary of `target` written on this host
// starts with.
std::string temporary_prefix(const fs::path& target)
{
    return "." + target.filename().string() + ".statmc-tmp-" + host_name() + "-";
}

// A hidden name in the target's directory, so that the final rename never crosses file
// systems and a crash leaves nothing that looks like the target; host and process in the
// name, so that writers on a shared file system never collide.
fs::path temporary_name(const fs::path& target)
{
    static std::atomic<int> serial{0};
    return directory_of(target) / (temporary_prefix(target) + std::to_string(::getpid()) + "-" +
                                   std::to_string(serial++));
}

// Temporaries of `target` that a process on this host left when it was killed (SIGKILL
// gives no chance to clean up): the next write of the target removes them.
void remove_stale_temporaries(const fs::path& target)
{
    const std::string prefix = temporary_prefix(target);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(directory_of(target), ec)) {
        const std::string name = entry.path().filename().string();
        if (name.compare(0, prefix.size(), prefix) != 0)
            continue;
        const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
        if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) {
            std::error_code ignored;
            fs::remove(entry.path(), ignored);
        }
    }
}

// fsync of a file or directory by name; errno's text on failure, "" on success.
std::string sync_path(const fs::path& path, int flags)
{
    const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
    if (fd < 0)
        return std::strerror(errno);
    const bool ok = ::fsync(fd) == 0;
    const int error = errno;
    ::close(fd);
    return ok ? std::string() : std::strerror(error);
}

}  // namespace

void write_file_atomically(const std::string& target,
                           const std::function<void(const std::string& temporary)>& write)
{
    const fs::path path(target);
    remove_stale_temporaries(path);
    TemporaryFile temporary(temporary_name(path));
    write(temporary.path().string());
    // On disk before the rename: after a crash the target is the old file or the new one.
    if (const std::string why = sync_path(temporary.path(), O_RDONLY); !why.empty())
        cannot_write(target, why);
    std::error_code ec;
    fs::rename(temporary.path(), path, ec);
    if (ec)
        cannot_write(target, ec.message());
    temporary.release();
    sync_path(directory_of(path), O_RDONLY | O_DIRECTORY);  // the rename itself; best effort
}

std::string storage_limit_reached(const std::string& path)
{
    // A write fails when the next block does not fit, so "full" is: less free than a block
    // of pixels may take (a few MB), not zero.
    constexpr std::uintmax_t kSlack = 4u << 20;
    std::error_code ec;
    std::uintmax_t size = fs::file_size(path, ec);
    if (ec)
        size = 0;
    // A write past the limit fills the file up to it; a file well short of it failed for
    // another reason.
    struct rlimit limit {};
    if (::getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
        size >= limit.rlim_cur - std::min<std::uintmax_t>(limit.rlim_cur / 2, 65536))
        return std::string(std::strerror(EFBIG)) + " (this process may write files of at most " +
               std::to_string(limit.rlim_cur) + " bytes: ulimit -f)";
    struct statvfs disk {};
    if (::statvfs(directory_of(fs::path(path)).c_str(), &disk) == 0) {
        const std::uintmax_t free_bytes = std::uintmax_t(disk.f_bavail) * disk.f_frsize;
        if (free_bytes < kSlack)
            return std::string(std::strerror(ENOSPC)) + " (" + std::to_string(free_bytes / 1024) +
                   " KB free)";
    }
    return {};
}

void remove_unfinished_temporaries() noexcept
{
    for (PendingSlot& slot : g_pending)
        if (slot.listed.load())
            ::unlink(slot.path);
}

extern "C" void remove_temporaries_and_end(int signal_number)
{
    remove_unfinished_temporaries();
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

void install_write_signal_handlers()
{
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction current {};
        if (::sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN)
            continue;  // nohup, or a background job of a shell: keep ignoring it
        std::signal(signal_number, remove_temporaries_and_end);
    }
    std::signal(SIGXFSZ, SIG_IGN);
}

void write_text_file_atomically(const std::string& target, const std::string& text)
{
    write_file_atomically(target, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        out.close();
        if (!out)
            cannot_write(target, std::strerror(errno));
    });
}

}  // namespace statmc::layers
