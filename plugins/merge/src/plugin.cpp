// merge: statistics images of one frame (render-farm tasks, different seeds) → the one
// image rendering all their samples at once would give, as a statmc plugin.
// Pops n statistics images (or the whole stack); pushes their merged statistics.
#include "statmc/merge/merge.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

void register_merge(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "merge";
    op.summary = "Pop K statistics images of one frame (e.g. farm tasks), push their exact "
                 "merge (counts add, moments combine; spp summed)";
    op.help = "Counts add and means, M2 and M3 combine by Chan et al. / Pebay, so the result "
              "equals one render with all the samples. The images must share resolution, "
              "data window, channels and statmc:formatVersion, and must not be denoised.";
    statmc::take_variadic_inputs(op, 2, "statistics images");
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const statmc::ParameterValues&,
                const statmc::RunContext& ctx) { return statmc::merge(inputs, ctx.nthreads); };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_merge)
