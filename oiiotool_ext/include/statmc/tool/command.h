// One entry of the command table: enough to parse an invocation, check it, run it and
// describe it in --help.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "statmc/plugin_host/modifiers.h"

namespace statmc::tool {

struct Command;
struct ToolContext;

/// A command as it appears on the command line, parsed.
struct Invocation {
    const Command* command = nullptr;
    std::string name;               ///< as typed, without modifiers: "--denoise"
    std::vector<std::string> args;  ///< the fixed number of positional arguments
    host::Modifiers modifiers;
};

struct Command {
    std::string name;                    ///< "-i", "--denoise"
    std::vector<std::string> aliases;    ///< other spellings: "-h" for "--help"
    std::vector<std::string> arg_names;  ///< positional arguments, e.g. {"FILE"}
    std::string optional_arg_name;       ///< one more argument taken when present ("--help OP")
    std::string summary;
    std::vector<host::ModifierSpec> modifiers;
    /// Runs as soon as it is parsed and ends the program (--help, --version).
    bool immediate = false;
    /// Checks arguments and modifier values before anything runs; throws HostError.
    std::function<void(const Invocation&)> check;
    /// Does the work on the image stack; throws HostError.
    std::function<void(ToolContext&, const Invocation&)> run;
};

}  // namespace statmc::tool
