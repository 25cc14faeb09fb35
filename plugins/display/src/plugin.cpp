// display: scene-linear → display encoding through OpenColorIO, as a statmc plugin.
// The parameter table is `statmc --help display`, generated from the specs below.
// One input; pushes the display-encoded R,G,B (A kept).
#include "statmc/display/display.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

void register_display(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "display";
    op.summary = "Convert the top image from scene-linear to a display through an OCIO view";
    op.help = "Uses :config=, else $OCIO, else the small config shipped with statmc (display "
              "sRGB with views sRGB, Filmic and Raw). Only R,G,B change; A is kept.";
    op.parameters = {
        statmc::string_parameter("display", "", "OCIO display (default: the config's)"),
        statmc::string_parameter("view", "", "OCIO view (default: the display's)"),
        statmc::string_parameter("config", "",
                                 "OCIO config file (default: $OCIO, else "
                                 "statmc's own)"),
    };
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const statmc::ParameterValues& p,
                const statmc::RunContext& ctx) {
        statmc::DisplayOptions options;
        options.config = statmc::display_config(p.get_string("config"), ctx.module);
        options.display = p.get_string("display");
        options.view = p.get_string("view");
        return statmc::display(*inputs[0], options, ctx.nthreads);
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_display)
