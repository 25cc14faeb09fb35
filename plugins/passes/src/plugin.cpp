// passes: K plain renders of one frame (different seeds) → a statistics image, as a
// statmc plugin.
// Pops n renders (or the whole stack); pushes mean, variance.* and sampleCount.Y = K.
#include "statmc/layers/renderer_presets.h"
#include "statmc/passes/passes.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

void register_passes(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "passes";
    op.summary = "Pop K independent renders of one frame, push their statistics "
                 "(mean, variance, sampleCount = K)";
    op.help = "Each render counts as one sample of every pixel; denoising the result tests "
              "the untransformed means with df = 2K - 2. The renders must share the data "
              "window and channel names.";
    statmc::take_variadic_inputs(op, 2, "renders");
    op.parameters.push_back(statmc::choice_parameter(
        "from", statmc::layers::renderer_preset_choices(), statmc::PassesOptions{}.from,
        "whose channel names the renders have: auto recognises Blender Cycles' multilayer "
        "files (ViewLayer.Combined or Noisy Image, Denoising Albedo/Normal/Depth as the "
        "guides) and other renderers' (docs/renderers.md); or name one"));
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const statmc::ParameterValues& p,
                const statmc::RunContext& ctx) {
        statmc::PassesOptions options;
        options.from = p.get_string("from", options.from);
        return statmc::passes(inputs, options, {}, ctx.nthreads);
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_passes)
