// The operators a host gets from plugin modules: the modules beside the running program (a
// `plugins` directory next to it, or ../lib/statmc/plugins when installed; for the Python
// module, the prefix it is installed in) and those in the directories of
// $STATMC_PLUGIN_PATH, loaded once; and their help pages.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "statmc/plugin_sdk/plugin_registry.h"

namespace statmc::host {

/// The directories searched, in order: the shipped modules, then $STATMC_PLUGIN_PATH.
std::vector<std::string> plugin_search_path();

/// Every operator, loaded on first use. Throws HostError naming the module that failed.
const statmc::PluginRegistry& plugin_registry();

/// `statmc --list-ops`: one line per operator.
std::string operator_list_text();

/// `statmc --help OP`: the operator's usage, help and parameter table. Throws HostError
/// for an unknown operator.
std::string operator_help_text(std::string_view name);

}  // namespace statmc::host
