// --ch, --chnames, --chappend: selecting, renaming and joining channels.
#include <OpenImageIO/imagebufalgo.h>

#include "channel_selection.h"
#include "statmc/plugin_host/text_split.h"
#include "statmc/tool/command_table.h"
#include "subimage_loop.h"
#include "tool_context.h"

namespace statmc::tool {

Command ch_command()
{
    Command c;
    c.name = "--ch";
    c.arg_names = {"CHANLIST"};
    c.summary = "Keep, reorder, rename or add channels: names, indices, new=old, new=value "
                "(e.g. R,G,B,A=1 or var.R=variance.R)";
    c.modifiers = {subimages_modifier()};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            return select_channels(*in[0], inv.args[0], inv.name, ctx.nthreads);
        });
    };
    return c;
}

Command chnames_command()
{
    Command c;
    c.name = "--chnames";
    c.arg_names = {"NAMELIST"};
    c.summary = "Rename the channels in order; an empty entry keeps a name (e.g. ,,,A)";
    c.modifiers = {subimages_modifier()};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const std::vector<std::string> names = host::split_text(inv.args[0]);
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            OIIO::ImageBuf renamed = *in[0];
            OIIO::ImageSpec& spec = renamed.specmod();
            for (std::size_t ch = 0; ch < names.size() && ch < spec.channelnames.size(); ++ch)
                if (!names[ch].empty())
                    spec.channelnames[ch] = names[ch];
            return renamed;
        });
    };
    return c;
}

Command chappend_command()
{
    Command c;
    c.name = "--chappend";
    c.summary = "Append the channels of the top image to those of the one below it (:n= "
                "joins the top n, bottom first)";
    c.modifiers = {statmc::int_parameter("n", 2, "how many images to join").at_least(2),
                   subimages_modifier()};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const int n = inv.modifiers.get_int("n");
        // Joined from the top down, as oiiotool does: a repeated name is renamed
        // ("channel1") within the upper images first.
        apply_to_subimages(ctx, inv, std::size_t(n), [&](const auto& in) {
            const std::size_t top = in.size() - 1;
            OIIO::ImageBuf joined = OIIO::ImageBufAlgo::channel_append(*in[top - 1], *in[top],
                                                                       OIIO::ROI(), ctx.nthreads);
            for (std::size_t k = top - 1; k-- > 0 && !joined.has_error();)
                joined =
                    OIIO::ImageBufAlgo::channel_append(*in[k], joined, OIIO::ROI(), ctx.nthreads);
            return joined;
        });
    };
    return c;
}

}  // namespace statmc::tool
