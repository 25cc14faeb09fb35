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
/// plugins on first use (and throws HostError if one fails).
const Command* find_command(std::string_view name);

std::string help_text();
std::string version_text();

// Each command is defined beside its handler (src/commands/), one file per group.
// io_commands.cpp
Command input_command();
Command output_command();
Command data_format_command();
Command compression_command();
Command max_memory_command();
Command frames_command();
Command skip_missing_command();
Command check_inputs_command();
// channel_commands.cpp
Command ch_command();
Command chnames_command();
Command chappend_command();
// subimage_commands.cpp
Command all_subimages_command();
Command subimage_command();
Command siappend_command();
Command dup_command();
// arithmetic_commands.cpp
Command add_command();
Command sub_command();
Command mul_command();
Command addc_command();
Command mulc_command();
// color_commands.cpp
Command colorconfig_command();
Command colorconvert_command();
Command ociodisplay_command();
// geometry_commands.cpp
Command crop_command();
Command resize_command();
// inspection_commands.cpp
Command info_command();
Command verbose_command();
Command stats_command();
Command diff_command();
// info_commands.cpp
Command echo_command();
Command list_ops_command();
Command threads_command();
Command help_command();
Command validate_command();
Command version_command();

}  // namespace statmc::tool
