#include "tool.h"

#include <new>

#include "plugin_commands.h"
#include "statmc/layers/file_error.h"
#include "statmc/tool/command_line.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/tool_error.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

int run_program(const std::vector<std::string>& args, ToolContext& ctx)
{
    plugin_commands();  // a broken module is reported before anything else
    if (args.empty()) {
        ctx.out << help_text();
        return 0;
    }
    const std::vector<Invocation> program = parse_program(args);
    // An immediate command (--help) runs alone: what came before it is only parsed.
    if (program.back().command->immediate) {
        program.back().command->run(ctx, program.back());
        return 0;
    }
    for (const Invocation& inv : program)
        inv.command->run(ctx, inv);
    return ctx.exit_code;
}

}  // namespace

int run_tool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
    ToolContext ctx(out);
    try {
        return run_program(args, ctx);
    } catch (const ToolError& e) {
        err << "statmc: error: " << e.what() << "\n";
    } catch (const layers::FileError& e) {
        err << "statmc: error: " << e.what() << "\n";
    } catch (const std::bad_alloc&) {
        err << "statmc: error: out of memory\n";
    } catch (const std::exception& e) {
        err << "statmc: error: internal error: " << e.what() << "\n";
    } catch (...) {
        err << "statmc: error: internal error\n";
    }
    return 1;
}

}  // namespace statmc::tool
