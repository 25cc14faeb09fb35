// --add, --sub, --mul (two images) and --addc, --mulc (an image and constants), through
// ImageBufAlgo.
#include <OpenImageIO/imagebufalgo.h>

#include "statmc/plugin_host/number_parsing.h"
#include "statmc/plugin_host/text_split.h"
#include "statmc/tool/command_table.h"
#include "subimage_loop.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

using ImageOp = OIIO::ImageBuf (*)(OIIO::Image_or_Const, OIIO::Image_or_Const, OIIO::ROI, int);

std::vector<float> constant_list(const std::string& text, const std::string& command)
{
    std::vector<float> values;
    for (const std::string& item : host::split_text(text))
        values.push_back(float(host::parse_float(item, command)));
    return values;
}

// oiiotool's rule: one value is used for every channel; a shorter list leaves the
// remaining channels alone (`identity`), a longer one is cut.
std::vector<float> per_channel(std::vector<float> values, int nchannels, float identity)
{
    if (values.size() == 1)
        return std::vector<float>(std::size_t(nchannels), values[0]);
    values.resize(std::size_t(nchannels), identity);
    return values;
}

Command image_pair_command(const char* name, const char* summary, ImageOp op)
{
    Command c;
    c.name = name;
    c.summary = summary;
    c.modifiers = {subimages_modifier()};
    c.run = [op](ToolContext& ctx, const Invocation& inv) {
        apply_to_subimages(ctx, inv, 2,
                           [&](const auto& in) { return op(*in[0], *in[1], {}, ctx.nthreads); });
    };
    return c;
}

Command constant_command(const char* name, const char* summary, ImageOp op, float identity)
{
    Command c;
    c.name = name;
    c.arg_names = {"VAL"};
    c.summary = summary;
    c.modifiers = {subimages_modifier()};
    c.check = [](const Invocation& inv) { constant_list(inv.args[0], inv.name); };
    c.run = [op, identity](ToolContext& ctx, const Invocation& inv) {
        const std::vector<float> given = constant_list(inv.args[0], inv.name);
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            const std::vector<float> values = per_channel(given, in[0]->nchannels(), identity);
            return op(*in[0], OIIO::cspan<float>(values), {}, ctx.nthreads);
        });
    };
    return c;
}

}  // namespace

Command add_command()
{
    return image_pair_command("--add", "Add the top two images", OIIO::ImageBufAlgo::add);
}

Command sub_command()
{
    return image_pair_command("--sub", "Subtract the top image from the one below it",
                              OIIO::ImageBufAlgo::sub);
}

Command mul_command()
{
    return image_pair_command("--mul", "Multiply the top two images", OIIO::ImageBufAlgo::mul);
}

Command addc_command()
{
    return constant_command("--addc", "Add a constant, or one per channel (0.5 or 1,0.5,0.25)",
                            OIIO::ImageBufAlgo::add, 0.f);
}

Command mulc_command()
{
    return constant_command("--mulc",
                            "Multiply by a constant, or one per channel (0.5 or 1,0.5,0.25)",
                            OIIO::ImageBufAlgo::mul, 1.f);
}

}  // namespace statmc::tool
