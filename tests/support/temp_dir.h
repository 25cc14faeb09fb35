// A fresh directory per test under the system temp dir, removed with its contents.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace statmc::test {

class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const std::filesystem::path& path() const { return path_; }
    /// path()/name as a string, for OIIO and command lines.
    std::string file(const std::string& name) const;
    /// Names of the entries in the directory, sorted (hidden files included).
    std::vector<std::string> entries() const;

private:
    std::filesystem::path path_;
};

/// The bytes of the file at `path` ("" when it cannot be read).
std::string file_bytes(const std::string& path);

}  // namespace statmc::test
