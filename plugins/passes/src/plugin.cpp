// passes: K plain renders of one frame (different seeds) → a statistics image, as a
// statmc plugin.
//
// | parameter | type | default      | range | meaning                    |
// |-----------|------|--------------|-------|----------------------------|
// | n         | int  | (the stack)  | >= 2  | number of renders popped   |
//
// Pops n renders (or the whole stack); pushes mean, variance.* and sampleCount.Y = K.
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
    op.parameters = {statmc::int_parameter("n", std::nullopt,
                                           "number of renders popped; without it, the whole "
                                           "stack")
                         .at_least(2)};
    op.inputs = statmc::kVariadicInputs;
    op.min_inputs = 2;
    op.input_noun = "renders";
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const statmc::ParameterValues&,
                const statmc::RunContext& ctx) {
        return statmc::passes(inputs, {}, ctx.nthreads);
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_passes)
