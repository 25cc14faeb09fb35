// --help, --version, --validate, --threads and --echo: commands that touch no image.
#include <OpenImageIO/imageio.h>

#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/number_parsing.h"
#include "statmc/plugin_host/plugin_catalog.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/plugin_commands.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

constexpr int kMaxThreads = 4096;

int thread_argument(const Invocation& inv)
{
    const int n = host::parse_int(inv.args[0], inv.name);
    if (n < 0 || n > kMaxThreads)
        throw host::HostError(inv.name + ": thread count must be in [0, " +
                              std::to_string(kMaxThreads) + "], got " + std::to_string(n));
    return n;
}

}  // namespace

Command threads_command()
{
    Command c;
    c.name = "--threads";
    c.arg_names = {"N"};
    c.summary = "Use N threads for the commands that follow (0 = all cores)";
    c.check = [](const Invocation& inv) { thread_argument(inv); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.nthreads = thread_argument(inv);
        OIIO::attribute("threads", ctx.nthreads);
    };
    return c;
}

Command help_command()
{
    Command c;
    c.name = "--help";
    c.aliases = {"-h"};
    c.optional_arg_name = "OP";
    c.summary = "Print this help, or an operator's parameters (--help OP), and exit";
    c.immediate = true;
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.out << (inv.args.empty() ? help_text() : host::operator_help_text(inv.args[0]));
    };
    return c;
}

Command list_ops_command()
{
    Command c;
    c.name = "--list-ops";
    c.summary = "List the operators the plugins provide and exit";
    c.immediate = true;
    c.run = [](ToolContext& ctx, const Invocation&) { ctx.out << host::operator_list_text(); };
    return c;
}

Command echo_command()
{
    Command c;
    c.name = "--echo";
    c.arg_names = {"TEXT"};
    c.summary = "Print TEXT (:newline=0 leaves out the line end)";
    c.modifiers = {statmc::bool_parameter("newline", true, "end with a new line")};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.out << inv.args[0] << (inv.modifiers.get_bool("newline") ? "\n" : "");
    };
    return c;
}

Command validate_command()
{
    Command c;
    c.name = "--validate";
    c.summary = "Check the commands before it (their arguments, modifiers and the operators' "
                "parameter ranges) and exit without reading or writing an image";
    c.immediate = true;
    // parse_program has checked every command before this one when it runs.
    c.run = [](ToolContext& ctx, const Invocation&) {
        ctx.out << "statmc: the command line is valid\n";
    };
    return c;
}

Command version_command()
{
    Command c;
    c.name = "--version";
    c.summary = "Print the version and exit";
    c.immediate = true;
    c.run = [](ToolContext& ctx, const Invocation&) { ctx.out << version_text(); };
    return c;
}

}  // namespace statmc::tool
