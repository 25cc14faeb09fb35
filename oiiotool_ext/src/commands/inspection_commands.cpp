// --info, --stats, -v and --diff: reports on images, printed as oiiotool prints them
// (image_report.h). --info and --stats are flags, as in oiiotool: they report each input
// read after them.
#include "image_report.h"
#include "statmc/tool/command_table.h"
#include "tool_context.h"

namespace statmc::tool {

Command info_command()
{
    Command c;
    c.name = "--info";
    c.summary = "Print the size, channels and type of every input read after this (with -v or "
                ":verbose=1: channel list, windows and metadata)";
    c.modifiers = {statmc::bool_parameter("verbose", false, "the metadata too, as with -v")};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.print_info = true;
        ctx.info_verbose = ctx.info_verbose || inv.modifiers.get_bool("verbose");
    };
    return c;
}

Command verbose_command()
{
    Command c;
    c.name = "-v";
    c.summary = "Verbose: name each file read and written; --info prints metadata";
    c.run = [](ToolContext& ctx, const Invocation&) { ctx.verbose = true; };
    return c;
}

Command stats_command()
{
    Command c;
    c.name = "--stats";
    c.summary = "Print pixel statistics (min, max, mean, standard deviation, NaN/Inf counts) "
                "of every input read after this";
    c.run = [](ToolContext& ctx, const Invocation&) { ctx.print_stats = true; };
    return c;
}

Command diff_command()
{
    Command c;
    c.name = "--diff";
    c.summary = "Compare the top two images (threshold 1e-6) and print the report; a FAILURE "
                "makes statmc exit with 1. The stack is left as it was";
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        std::vector<StackImage> both = ctx.stack.pop(2, inv.name);
        if (!print_diff(ctx.out, both[0], both[1], ctx.nthreads))
            ctx.exit_code = 1;
        for (StackImage& image : both)
            ctx.stack.push(std::move(image));
    };
    return c;
}

}  // namespace statmc::tool
