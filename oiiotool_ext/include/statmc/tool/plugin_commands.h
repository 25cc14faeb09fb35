// The operators statmc gets from plugin modules, and their commands: the modules beside
// the executable (a `plugins` directory next to it, or ../lib/statmc/plugins when
// installed) and those in the directories of $STATMC_PLUGIN_PATH.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "statmc/plugin_sdk/plugin_registry.h"
#include "statmc/tool/command.h"

namespace statmc::tool {

/// The directories searched, in order: the shipped modules, then $STATMC_PLUGIN_PATH.
std::vector<std::string> plugin_search_path();

/// Every operator, loaded on first use. Throws ToolError naming the module that failed.
const statmc::PluginRegistry& plugin_registry();

/// One command per operator ("--denoise"), its modifiers the operator's parameters.
const std::vector<Command>& plugin_commands();

/// The command for `op`: pops its inputs, runs it, pushes the result.
Command operator_command(const statmc::OperatorSpec& op);

/// `statmc --list-ops`: one line per operator.
std::string operator_list_text();

/// `statmc --help OP`: the operator's usage, help and parameter table. Throws ToolError
/// for an unknown operator.
std::string operator_help_text(std::string_view name);

}  // namespace statmc::tool
