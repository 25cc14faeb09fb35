// The statmc program: parse, check, run; every failure is one message and exit code 1.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace statmc::tool {

/// Runs the command line `args` (without the program name). Help and version go to
/// `out`; errors go to `err` as "statmc: error: <message>". Returns the exit code.
int run_tool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace statmc::tool
