// --colorconfig, --colorconvert, --ociodisplay: colour management through OIIO's OCIO
// support. The config is --colorconfig's file, else $OCIO, else OIIO's built-in spaces
// (linear, sRGB, Rec709), as oiiotool chooses.
#include <cstdlib>
#include <memory>

#include <OpenImageIO/color.h>
#include <OpenImageIO/imagebufalgo.h>

#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_table.h"
#include "subimage_loop.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

// Whether a config file is named (--colorconfig or $OCIO), rather than OIIO's built-in
// spaces.
bool config_named(const ToolContext& ctx)
{
    const char* env = std::getenv("OCIO");
    return !ctx.colorconfig.empty() || (env && *env);
}

std::shared_ptr<OIIO::ColorConfig> load_color_config(const ToolContext& ctx,
                                                     const std::string& command)
{
    auto config = std::make_shared<OIIO::ColorConfig>(ctx.colorconfig);
    // With neither a file nor $OCIO, OIIO reports the missing file but works with its
    // built-in spaces, as oiiotool does; only a named config must load.
    if (!config_named(ctx))
        config->geterror();
    else if (config->has_error())
        throw host::HostError(
            command + ": colour config " +
            (ctx.colorconfig.empty() ? std::string("from $OCIO") : ctx.colorconfig) + ": " +
            config->geterror());
    return config;
}

// The config the colour commands use, loaded once (the first use, or --colorconfig).
OIIO::ColorConfig& color_config(ToolContext& ctx, const std::string& command)
{
    if (!ctx.color_config)
        ctx.color_config = load_color_config(ctx, command);
    return *ctx.color_config;
}

// Off by default, as in oiiotool (ImageBufAlgo's own default is on).
host::ModifierSpec unpremult_modifier()
{
    return statmc::bool_parameter("unpremult", false, "divide by alpha around the conversion");
}

}  // namespace

Command colorconfig_command()
{
    Command c;
    c.name = "--colorconfig";
    c.arg_names = {"FILE"};
    c.summary = "The OCIO config for the colour commands that follow (default: $OCIO, else "
                "OIIO's built-in linear/sRGB/Rec709)";
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.colorconfig = inv.args[0];
        ctx.color_config = load_color_config(ctx, inv.name);  // a bad file fails here, naming it
    };
    return c;
}

Command colorconvert_command()
{
    Command c;
    c.name = "--colorconvert";
    c.arg_names = {"FROM", "TO"};
    c.summary = "Convert the colour channels (the first three, and alpha) from one colour "
                "space to another";
    c.modifiers = {unpremult_modifier(), subimages_modifier()};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        OIIO::ColorConfig& config = color_config(ctx, inv.name);
        const bool unpremult = inv.modifiers.get_bool("unpremult");
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            return OIIO::ImageBufAlgo::colorconvert(*in[0], inv.args[0], inv.args[1], unpremult, "",
                                                    "", &config, OIIO::ROI(), ctx.nthreads);
        });
    };
    return c;
}

Command ociodisplay_command()
{
    Command c;
    c.name = "--ociodisplay";
    c.arg_names = {"DISPLAY", "VIEW"};
    c.summary = "Apply an OCIO display and view (\"\" = the config's default) to the colour "
                "channels";
    c.modifiers = {statmc::string_parameter("from", "",
                                            "the image's colour space (default: "
                                            "its oiio:ColorSpace, else scene_linear)"),
                   statmc::string_parameter("looks", "", "OCIO looks to apply"),
                   unpremult_modifier(), subimages_modifier()};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        // The built-in spaces have no displays; OIIO would fail (or crash on the
        // defaults) without a config.
        if (!config_named(ctx))
            throw host::HostError(inv.name +
                                  ": needs an OCIO config (--colorconfig FILE or $OCIO)");
        OIIO::ColorConfig& config = color_config(ctx, inv.name);
        auto text = [](const char* s) { return std::string(s ? s : ""); };
        std::string display = inv.args[0], view = inv.args[1];
        if (display.empty())
            display = text(config.getDefaultDisplayName());
        if (view.empty())  // IBA refuses an empty view (docs/ecosystem.md pitfall 8)
            view = text(config.getDefaultViewName(display));
        const std::string from = inv.modifiers.values().get_string("from");
        const std::string looks = inv.modifiers.values().get_string("looks");
        const bool unpremult = inv.modifiers.get_bool("unpremult");
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            return OIIO::ImageBufAlgo::ociodisplay(*in[0], display, view, from, looks, unpremult,
                                                   "", "", &config, OIIO::ROI(), ctx.nthreads);
        });
    };
    return c;
}

}  // namespace statmc::tool
