// The statmc commands of the plugin operators (statmc/plugin_host/plugin_catalog.h finds
// and loads them): one command per operator, which pops its inputs, runs it and pushes the
// result.
#pragma once

#include <vector>

#include "statmc/plugin_sdk/operator_spec.h"
#include "statmc/tool/command.h"

namespace statmc::tool {

/// One command per operator ("--denoise"), its modifiers the operator's parameters.
const std::vector<Command>& plugin_commands();

/// The command for `op`: pops its inputs, runs it, pushes the result.
Command operator_command(const statmc::OperatorSpec& op);

}  // namespace statmc::tool
