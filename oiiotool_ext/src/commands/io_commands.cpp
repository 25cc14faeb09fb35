// -i and -o: images between files and the stack.
#include "statmc/tool/command_table.h"
#include "statmc/layers/exr_files.h"
#include "statmc/tool/tool_context.h"

namespace statmc::tool {

Command input_command()
{
    Command c;
    c.name = "-i";
    c.arg_names = {"FILE"};
    c.summary = "Read an image and push it on the stack (a bare FILE does the same)";
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.stack.push({layers::read_image_file(inv.args[0]), inv.args[0]});
    };
    return c;
}

Command output_command()
{
    Command c;
    c.name = "-o";
    c.arg_names = {"FILE"};
    c.summary = "Write the top image to an OpenEXR file (float, lossless; via a temporary "
                "file, so a failed write leaves no file)";
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        layers::write_image_file(ctx.stack.top(inv.name).image, inv.args[0]);
    };
    return c;
}

}  // namespace statmc::tool
