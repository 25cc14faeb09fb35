// merge: statistics images of one frame (render-farm tasks, different seeds) → the one
// image rendering all their samples at once would give, as a statmc plugin.
// Pops n statistics images (or the whole stack); pushes their merged statistics.
#include <string>

#include "statmc/layers/layer_names.h"
#include "statmc/merge/merge.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

// The user learns that the merge holds only part of the frame's samples.
void note_partial(const OIIO::ImageBuf& result, const statmc::MergeOptions& options,
                  const statmc::RunContext& ctx)
{
    if (!options.allow_partial || result.has_error())
        return;
    const int missing = result.spec().get_int_attribute(statmc::layers::attr::kTasksMissing, 0);
    if (missing > 0)
        ctx.tell("--merge: note: " + std::to_string(missing) +
                 (missing == 1 ? " task is" : " tasks are") +
                 " missing; merged the samples of the others (statmc:tasksMissing)");
}

void register_merge(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "merge";
    op.summary = "Pop K statistics images of one frame (e.g. farm tasks), push their exact "
                 "merge (counts add, moments combine; spp summed)";
    op.help = "Counts add and means, M2 and M3 combine by Chan et al. / Pebay, so the result "
              "equals one render with all the samples. The images must share resolution, "
              "data window, channels and statmc:formatVersion, and must not be denoised.";
    op.help += " Farm tasks (statmc-render --task I/N) must form a complete set, and two "
               "parts with one seed must not share samples (docs/farm.md).";
    op.parameters = {statmc::bool_parameter(
        "allow_partial", false,
        "merge an incomplete task set (tasks missing or stopped early); the header's "
        "statmc:tasksMissing and a note on stderr say what is missing")};
    statmc::take_variadic_inputs(op, 1, "statistics images");
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const statmc::ParameterValues& p,
                const statmc::RunContext& ctx) {
        statmc::MergeOptions options;
        options.allow_partial = p.get_bool("allow_partial");
        OIIO::ImageBuf result = statmc::merge(inputs, options, ctx.nthreads);
        note_partial(result, options, ctx);
        return result;
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_merge)
