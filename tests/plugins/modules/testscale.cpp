// A plugin built only in the test tree: --testscale multiplies every channel by `factor`
// (or divides with :reciprocal=1). It shows a third-party module found on
// $STATMC_PLUGIN_PATH working exactly like a shipped one.
//
// | parameter  | type  | default | range       | meaning                   |
// |------------|-------|---------|-------------|---------------------------|
// | factor     | float | 2       | [0.01, 100] | the scale                 |
// | reciprocal | bool  | 0       |             | divide instead            |
#include <OpenImageIO/imagebufalgo.h>

#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

void register_testscale(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "testscale";
    op.summary = "Multiply every channel of the top image by a factor (a test plugin)";
    op.help = "Exists to test plugin loading.";
    op.parameters = {
        statmc::float_parameter("factor", 2.0, "the scale").between(0.01, 100),
        statmc::bool_parameter("reciprocal", false, "divide by the factor instead"),
    };
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs,
                const statmc::ParameterValues& p, const statmc::RunContext& ctx) {
        const double factor = p.get_float("factor", 2.0);
        const float scale = float(p.get_bool("reciprocal") ? 1 / factor : factor);
        return OIIO::ImageBufAlgo::mul(*inputs[0], scale, {}, ctx.nthreads);
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_testscale)
