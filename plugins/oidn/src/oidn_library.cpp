#include "oidn_library.h"

#include <dlfcn.h>
#include <glob.h>

#include <cstdlib>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace statmc::oidn_api {

namespace {

constexpr const char* kSoname = "libOpenImageDenoise.so.2";

// $VIRTUAL_ENV/lib/python3.*/site-packages/pyoidn/oidn/lib/<soname>: where pip puts it.
std::vector<std::string> virtual_env_candidates()
{
    std::vector<std::string> found;
    const char* venv = std::getenv("VIRTUAL_ENV");
    if (!venv || !*venv)
        return found;
    const std::string pattern =
        std::string(venv) + "/lib/python3*/site-packages/pyoidn/oidn/lib/" + kSoname;
    glob_t g{};
    if (glob(pattern.c_str(), 0, nullptr, &g) == 0)
        for (std::size_t i = 0; i < g.gl_pathc; ++i)
            found.emplace_back(g.gl_pathv[i]);
    globfree(&g);
    return found;
}

template <class F>
void resolve(void* handle, const char* name, F& out, const std::string& where)
{
    out = reinterpret_cast<F>(dlsym(handle, name));
    if (!out)
        throw std::runtime_error(where + " has no " + name + ": it is not OIDN 2");
}

Functions functions_of(void* handle, const std::string& where)
{
    Functions f{};
    resolve(handle, "oidnNewDevice", f.new_device, where);
    resolve(handle, "oidnSetDeviceInt", f.set_device_int, where);
    resolve(handle, "oidnCommitDevice", f.commit_device, where);
    resolve(handle, "oidnReleaseDevice", f.release_device, where);
    resolve(handle, "oidnGetDeviceError", f.get_device_error, where);
    resolve(handle, "oidnNewFilter", f.new_filter, where);
    resolve(handle, "oidnSetSharedFilterImage", f.set_shared_filter_image, where);
    resolve(handle, "oidnSetFilterBool", f.set_filter_bool, where);
    resolve(handle, "oidnCommitFilter", f.commit_filter, where);
    resolve(handle, "oidnExecuteFilter", f.execute_filter, where);
    resolve(handle, "oidnReleaseFilter", f.release_filter, where);
    return f;
}

// The first of `candidates` that loads; the loader's messages of all that did not.
void* open_first(const std::vector<std::string>& candidates, std::string& where,
                 std::string& failures)
{
    for (const std::string& path : candidates) {
        if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
            where = path;
            return handle;
        }
        const char* why = dlerror();
        failures += "\n  " + path + ": " + (why ? why : "not loadable");
    }
    return nullptr;
}

}  // namespace

std::string search_text()
{
    return std::string("$STATMC_OIDN_LIBRARY, else ") + kSoname +
           " on the loader's path (a system install, LD_LIBRARY_PATH), else pyoidn's copy in "
           "the Python virtual environment $VIRTUAL_ENV";
}

const Functions& load(const std::string& path)
{
    static std::mutex mutex;
    static std::map<std::string, Functions> loaded;
    const std::lock_guard<std::mutex> lock(mutex);
    std::vector<std::string> candidates;
    if (!path.empty()) {
        candidates.push_back(path);
    } else if (const char* env = std::getenv("STATMC_OIDN_LIBRARY"); env && *env) {
        candidates.push_back(env);
    } else {
        candidates.push_back(kSoname);
        for (const std::string& c : virtual_env_candidates())
            candidates.push_back(c);
    }
    const std::string key = candidates.front();
    if (const auto it = loaded.find(key); it != loaded.end())
        return it->second;
    std::string where, failures;
    void* handle = open_first(candidates, where, failures);
    if (!handle)
        throw std::runtime_error(
            "OIDN (Intel Open Image Denoise 2) is not installed where statmc looks (" +
            search_text() + "):" + failures +
            "\nInstall it with `python3 -m pip install pyoidn` (in a virtual environment) and "
            "point STATMC_OIDN_LIBRARY at <site-packages>/pyoidn/oidn/lib/" +
            kSoname);
    // Kept open for the process's life: OIDN's worker threads may outlive a call.
    return loaded.emplace(key, functions_of(handle, where)).first->second;
}

}  // namespace statmc::oidn_api
