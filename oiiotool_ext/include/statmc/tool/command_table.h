// The commands statmc knows, and the --help text generated from them.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "statmc/tool/command.h"

namespace statmc::tool {

/// The built-in commands; the operators come from plugins (plugin_commands.h).
const std::vector<Command>& command_table();

/// The built-in or operator command named or aliased `name`, or null. Loads the
/// plugins on first use (and throws ToolError if one fails).
const Command* find_command(std::string_view name);

std::string help_text();
std::string version_text();

// Each command is defined beside its handler (src/commands/).
Command input_command();
Command output_command();
Command list_ops_command();
Command threads_command();
Command help_command();
Command version_command();

}  // namespace statmc::tool
