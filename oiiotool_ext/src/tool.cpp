#include "tool.h"

#include <algorithm>
#include <new>
#include <string>

#include "sequence_run.h"
#include "statmc/layers/file_error.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_line.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/plugin_commands.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

// Each frame runs the program on a fresh stack; an error stops the run, naming the frame
// (the frames before it are written, its own output is not).
int run_frames(const SequenceRun& run, std::ostream& out)
{
    int exit_code = 0;
    for (int frame : run.frames()) {
        run.advance_to(frame);
        ToolContext ctx(out);
        try {
            for (const Invocation& inv : run.program_for(frame, ctx))
                inv.command->run(ctx, inv);
        } catch (const host::HostError& e) {
            throw host::HostError("frame " + std::to_string(frame) + ": " + e.what());
        } catch (const layers::FileError& e) {
            throw host::HostError("frame " + std::to_string(frame) + ": " + e.what());
        }
        exit_code = std::max(exit_code, ctx.exit_code);
    }
    return exit_code;
}

int run_program(const std::vector<std::string>& args, ToolContext& ctx, std::ostream& err)
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
    const SequenceRun run(program, err);
    if (run.active())
        return run_frames(run, ctx.out);
    for (const Invocation& inv : run.program())
        inv.command->run(ctx, inv);
    return ctx.exit_code;
}

}  // namespace

int run_tool(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
    ToolContext ctx(out);
    try {
        return run_program(args, ctx, err);
    } catch (const host::HostError& e) {
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
