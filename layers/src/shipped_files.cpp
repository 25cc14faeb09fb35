#include "statmc/layers/shipped_files.h"

#include <filesystem>
#include <system_error>

#include <dlfcn.h>
#include <sys/auxv.h>

namespace statmc::layers {

namespace fs = std::filesystem;

namespace {

// The shared object holding this code when it is not the main program (the Python
// module), else empty. glibc's dladdr names the main program by its argv[0], which is no
// path to it, so the main program is recognised by its entry point's load base.
fs::path host_module()
{
    Dl_info here{}, main_program{};
    if (!::dladdr(reinterpret_cast<void*>(&host_module), &here) || !here.dli_fname ||
        !::dladdr(reinterpret_cast<void*>(::getauxval(AT_ENTRY)), &main_program) ||
        here.dli_fbase == main_program.dli_fbase)
        return {};
    std::error_code ec;
    const fs::path module = fs::absolute(here.dli_fname, ec);
    return ec ? fs::path() : module;
}

}  // namespace

std::vector<std::string> shipped_paths(const std::string& name, const std::string& build_fallback)
{
    std::error_code ec;
    std::vector<fs::path> candidates;
    if (const fs::path module = host_module(); !module.empty()) {
        candidates = {module.parent_path() / ".." / ".." / ".." / "statmc" / name};
    } else {
        const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
        if (!ec)
            candidates = {exe.parent_path() / name,
                          exe.parent_path() / ".." / "lib" / "statmc" / name};
    }
    std::vector<std::string> found;
    for (const fs::path& path : candidates)
        if (fs::exists(path, ec))
            found.push_back(path.lexically_normal().string());
    if (found.empty() && !build_fallback.empty() && fs::exists(build_fallback, ec))
        found.push_back(build_fallback);
    return found;
}

}  // namespace statmc::layers
