#include "statmc/layers/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "statmc/layers/file_error.h"

namespace statmc::layers {

namespace fs = std::filesystem;

namespace {

// Removes the temporary file unless the write got as far as renaming it.
class TemporaryFile {
public:
    explicit TemporaryFile(fs::path path) : path_(std::move(path)) {}
    ~TemporaryFile()
    {
        if (!path_.empty()) {
            std::error_code ignored;
            fs::remove(path_, ignored);
        }
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    const fs::path& path() const { return path_; }
    void release() { path_.clear(); }

private:
    fs::path path_;
};

[[noreturn]] void cannot_write(const std::string& path, const std::string& why)
{
    throw FileError(path + ": cannot write: " + why);
}

fs::path directory_of(const fs::path& target)
{
    return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// A hidden name in the target's directory, so that the final rename never crosses
// file systems and a crash leaves nothing that looks like the target.
fs::path temporary_name(const fs::path& target)
{
    static int serial = 0;
    return directory_of(target) / ("." + target.filename().string() + ".statmc-tmp-" +
                                   std::to_string(::getpid()) + "-" + std::to_string(serial++));
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

}  // namespace statmc::layers
