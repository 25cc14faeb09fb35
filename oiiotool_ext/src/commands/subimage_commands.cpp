// -a, --subimage, --siappend: the subimages (EXR parts) of stack images; --dup copies one.
#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_table.h"
#include "subimage_loop.h"
#include "tool_context.h"

namespace statmc::tool {

Command all_subimages_command()
{
    Command c;
    c.name = "-a";
    c.summary = "Apply the commands that follow to every subimage, not only the first";
    c.run = [](ToolContext& ctx, const Invocation&) { ctx.all_subimages = true; };
    return c;
}

Command subimage_command()
{
    Command c;
    c.name = "--subimage";
    c.arg_names = {"N|NAME"};
    c.summary = "Keep only one subimage of the top image, by index or part name; "
                ":delete=1 removes it instead";
    c.modifiers = {statmc::bool_parameter("delete", false, "remove the subimage, keep the rest")};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        StackImage image = ctx.stack.pop(inv.name);
        const std::size_t s = find_subimage(image, inv.args[0], inv.name);
        if (inv.modifiers.get_bool("delete")) {
            if (image.subimages.size() == 1)
                throw host::HostError(inv.name + ": " + image.label +
                                      " has one subimage; deleting it would leave no image");
            image.subimages.erase(image.subimages.begin() + std::ptrdiff_t(s));
            if (!image.mip_levels.empty())
                image.mip_levels.erase(image.mip_levels.begin() + std::ptrdiff_t(s));
        } else {
            // Moved, not copied: a copy of a failed ImageBuf is not safe in OIIO 2.4.
            OIIO::ImageBuf kept = std::move(image.subimages[s]);
            image.subimages.clear();
            image.subimages.push_back(std::move(kept));
            if (!image.mip_levels.empty()) {
                std::vector<OIIO::ImageBuf> levels = std::move(image.mip_levels[s]);
                image.mip_levels.clear();
                image.mip_levels.push_back(std::move(levels));
            }
        }
        image.label += " (" + inv.name + " " + inv.args[0] + ")";
        image.sequence.reset();
        ctx.stack.push(std::move(image));
    };
    return c;
}

Command siappend_command()
{
    Command c;
    c.name = "--siappend";
    c.summary = "Join the top two images into one image with the subimages of both (:n= "
                "joins the top n, bottom first)";
    c.modifiers = {statmc::int_parameter("n", 2, "how many images to join").at_least(2)};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        std::vector<StackImage> images =
            ctx.stack.pop(std::size_t(inv.modifiers.get_int("n")), inv.name);
        StackImage joined = std::move(images[0]);
        // MIP levels follow their subimages; a single-level subimage has none.
        joined.mip_levels.resize(joined.subimages.size());
        for (std::size_t k = 1; k < images.size(); ++k) {
            images[k].mip_levels.resize(images[k].subimages.size());
            for (std::size_t s = 0; s < images[k].subimages.size(); ++s) {
                joined.subimages.push_back(std::move(images[k].subimages[s]));
                joined.mip_levels.push_back(std::move(images[k].mip_levels[s]));
            }
        }
        joined.label += " (" + inv.name + ")";
        ctx.stack.push(std::move(joined));
    };
    return c;
}

}  // namespace statmc::tool

namespace statmc::tool {

Command dup_command()
{
    Command c;
    c.name = "--dup";
    c.summary = "Push a copy of the top image (every subimage): an operator that pops it "
                "leaves the original below, e.g. f.exr --dup --oidn --verify";
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const StackImage& top = ctx.stack.top(inv.name);
        StackImage copy;
        for (const OIIO::ImageBuf& image : top.subimages) {
            copy.subimages.emplace_back();
            if (!copy.subimages.back().copy(image))
                throw host::HostError(inv.name + ": " + copy.subimages.back().geterror());
        }
        copy.mip_levels = top.mip_levels;
        copy.label = top.label;
        copy.sequence = top.sequence;
        copy.frame = top.frame;
        ctx.stack.push(std::move(copy));
    };
    return c;
}

}  // namespace statmc::tool
