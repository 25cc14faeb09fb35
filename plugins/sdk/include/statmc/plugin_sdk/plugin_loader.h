// Host side of the plugin interface: finding and loading modules with dlopen.
#pragma once

#include <string>
#include <vector>

#include "statmc/plugin_sdk/plugin_registry.h"

namespace statmc {

/// Loads the module at `path` (dlopen RTLD_NOW | RTLD_LOCAL), checks its interface
/// version and lets it register its operators. Throws PluginError naming the file: for
/// dlerror's message, a missing entry point, another interface version (both named) or
/// an invalid registration. A loaded module stays loaded for the life of the process,
/// since the registry holds functions that live in it.
void load_plugin(const std::string& path, PluginRegistry& registry);

/// The modules (*.so) in `directory`, sorted by name; none when it does not exist.
std::vector<std::string> plugin_files(const std::string& directory);

/// "a:b::c" → {"a", "b", "c"}: a search path such as $STATMC_PLUGIN_PATH.
std::vector<std::string> split_search_path(const std::string& text);

}  // namespace statmc
