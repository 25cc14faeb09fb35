// Turning the argument list into invocations, left to right as oiiotool reads it: a bare
// argument is an input image, `--name[:mod=val...]` a command followed by its fixed
// number of positional arguments.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "statmc/tool/command.h"

namespace statmc::tool {

/// "--denoise:radius=3:alpha=0.01" → {"--denoise", {{"radius","3"}, {"alpha","0.01"}}}.
/// Throws HostError for an empty or value-less modifier.
std::pair<std::string, std::vector<std::pair<std::string, std::string>>>
split_command(const std::string& word);

/// Parses the invocation starting at args[i] and advances i past its arguments. A bare
/// argument becomes `-i <arg>`. Throws HostError for an unknown command, a missing
/// argument or a bad modifier.
Invocation parse_invocation(const std::vector<std::string>& args, std::size_t& i);

/// The whole command line, parsed and each invocation checked (Command::check), so that
/// a typo late on the line is reported before the first command runs. An immediate
/// command (--help, --version) ends the program: it is the last invocation returned, and
/// nothing after it is parsed. Throws HostError.
std::vector<Invocation> parse_program(const std::vector<std::string>& args);

}  // namespace statmc::tool
