// --passes: K renders on the stack become one statistics image.
#include "statmc/passes/passes.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/tool_context.h"
#include "statmc/tool/tool_error.h"

namespace statmc::tool {

namespace {

void check_count(const Invocation& inv)
{
    if (inv.modifiers.has("n") && inv.modifiers.get_int("n") < 2)
        throw ToolError(inv.name + ": n must be at least 2, got " +
                        std::to_string(inv.modifiers.get_int("n")));
}

}  // namespace

Command passes_command()
{
    Command c;
    c.name = "--passes";
    c.summary = "Pop K independent renders of one frame, push their statistics "
                "(mean, variance, sampleCount = K)";
    c.modifiers = {{"n", ModifierType::Int, "", "number of renders popped, >= 2; without it, "
                                                "the whole stack", {}, {}}};
    c.check = check_count;
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const std::size_t k =
            inv.modifiers.has("n") ? std::size_t(inv.modifiers.get_int("n")) : ctx.stack.size();
        if (k < 2)
            throw ToolError(inv.name + ": needs at least 2 renders on the stack, got " +
                            std::to_string(k));
        const std::vector<StackImage> renders = ctx.stack.pop(k, inv.name);
        std::vector<const OIIO::ImageBuf*> images;
        for (const StackImage& r : renders)
            images.push_back(&r.image);
        StackImage result{OIIO::ImageBuf(), "--passes result"};
        if (!statmc::passes(result.image, images, {}, ctx.nthreads))
            throw ToolError(inv.name + ": " + result.image.geterror());
        ctx.stack.push(std::move(result));
    };
    return c;
}

}  // namespace statmc::tool
