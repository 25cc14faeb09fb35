// `:name=value` modifiers → the typed parameter parser of the plugin SDK and the command's
// own check, for every command (the built-ins and each plugin operator). The first byte
// picks the command, the rest is the modifier text: "--denoise" + ":radius=3:alpha=0.01".
// A bad value must be a HostError naming the command and parameter; any other escape or
// a crash is a finding.
#include <cstdint>
#include <vector>

#include "fuzz_input.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_line.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/plugin_commands.h"

namespace {

const std::vector<const statmc::tool::Command*>& every_command()
{
    static const std::vector<const statmc::tool::Command*> commands = [] {
        std::vector<const statmc::tool::Command*> all;
        for (const auto& c : statmc::tool::command_table())
            all.push_back(&c);
        for (const auto& c : statmc::tool::plugin_commands())
            all.push_back(&c);
        return all;
    }();
    return commands;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size == 0)
        return 0;
    const auto& commands = every_command();
    const statmc::tool::Command& command = *commands[data[0] % commands.size()];
    if (command.immediate)
        return 0;  // --help and --version take no modifiers and print
    try {
        const auto [name, given] =
            statmc::tool::split_command(command.name + statmc::fuzz::as_text(data + 1, size - 1));
        statmc::tool::Invocation inv;
        inv.command = &command;
        inv.name = name;
        inv.modifiers = statmc::host::Modifiers::parse(name, given, command.modifiers);
        for (std::size_t a = 0; a < command.arg_names.size(); ++a)
            inv.args.push_back("in.exr");
        if (command.check)
            command.check(inv);
    } catch (const statmc::host::HostError&) {
    }
    return 0;
}
