#include "statmc/plugin_sdk/plugin_loader.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include <dlfcn.h>

#include "statmc/plugin_sdk/plugin_interface.h"

namespace statmc {

namespace {

using VersionFunction = int (*)();
using IdentityFunction = BuildIdentity (*)();
using RegisterFunction = void (*)(PluginRegistry&);

std::string last_dl_error()
{
    const char* message = dlerror();
    return message ? message : "unknown error";
}

void* entry_point(void* handle, const std::string& path, const char* symbol)
{
    dlerror();  // clear, so that a null symbol is told apart from a failure
    void* address = dlsym(handle, symbol);
    if (!address)
        throw PluginError(path + ": not a statmc plugin: no entry point " + symbol + " (" +
                          last_dl_error() + ")");
    return address;
}

// Registers into a staging registry first, so that a module whose registration fails
// part way leaves nothing behind and can be unloaded.
PluginRegistry staged_registration(void* handle, const std::string& path)
{
    const auto version = reinterpret_cast<VersionFunction>(
        entry_point(handle, path, "statmc_plugin_interface_version"));
    const int found = version();
    if (found != kPluginInterfaceVersion)
        throw PluginError(path + ": plugin interface version " + std::to_string(found) +
                          ", but this statmc needs version " +
                          std::to_string(kPluginInterfaceVersion) +
                          " (rebuild the plugin against this statmc)");
    const auto identity = reinterpret_cast<IdentityFunction>(
        entry_point(handle, path, "statmc_plugin_build_identity"));
    const std::string mismatch = build_identity_mismatch(identity(), this_build_identity());
    if (!mismatch.empty())
        throw PluginError(path + ": built differently from this statmc: " + mismatch +
                          " (rebuild the plugin against this statmc)");
    const auto register_plugin =
        reinterpret_cast<RegisterFunction>(entry_point(handle, path, "statmc_register_plugin"));
    PluginRegistry staged;
    staged.set_current_module(path);
    try {
        register_plugin(staged);
    } catch (const PluginError&) {
        throw;
    } catch (const std::exception& e) {
        throw PluginError(path + ": plugin registration failed: " + e.what());
    }
    return staged;
}

}  // namespace

void load_plugin(const std::string& path, PluginRegistry& registry)
{
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle)
        throw PluginError(path + ": cannot load plugin: " + last_dl_error());
    try {
        const PluginRegistry staged = staged_registration(handle, path);
        for (const OperatorSpec& op : staged.operators())
            if (const OperatorSpec* other = registry.find(op.name))
                throw PluginError(path + ": operator '" + op.name + "' is already registered by " +
                                  (other->module.empty() ? "the host" : other->module));
        registry.set_current_module(path);
        for (const OperatorSpec& op : staged.operators())
            registry.add(op);
        registry.set_current_module({});
    } catch (...) {
        dlclose(handle);  // nothing of it was kept
        throw;
    }
    // Otherwise the handle is deliberately never closed: the registry holds its functions.
}

std::vector<std::string> plugin_files(const std::string& directory)
{
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    std::error_code ec;
    for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".so" && it->is_regular_file(ec))
            files.push_back(it->path().string());
    std::sort(files.begin(), files.end());
    return files;
}

std::vector<std::string> split_search_path(const std::string& text)
{
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t colon = text.find(':', start);
        if (colon == std::string::npos)
            colon = text.size();
        if (colon > start)
            parts.push_back(text.substr(start, colon - start));
        start = colon + 1;
    }
    return parts;
}

}  // namespace statmc
