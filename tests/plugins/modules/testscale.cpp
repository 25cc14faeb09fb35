// A plugin built only in the test tree: --testscale multiplies every channel by `factor`
// (or divides with :reciprocal=1). It shows a third-party module found on
// $STATMC_PLUGIN_PATH working exactly like a shipped one. --testthrow breaks the
// operator contract on purpose (it throws), for the host's guard.
#include <stdexcept>

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
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const statmc::ParameterValues& p,
                const statmc::RunContext& ctx) {
        const double factor = p.get_float("factor", 2.0);
        const float scale = float(p.get_bool("reciprocal") ? 1 / factor : factor);
        return OIIO::ImageBufAlgo::mul(*inputs[0], scale, {}, ctx.nthreads);
    };
    registry.add(std::move(op));

    // Two operators, so that both of the host's calls are guarded: run, and run_in_place.
    auto fail = [](const statmc::ParameterValues& p) {
        if (p.get_bool("not_std"))
            throw 42;
        throw std::runtime_error("deliberate failure");
    };
    statmc::OperatorSpec bad;
    bad.name = "testthrow";
    bad.summary = "Throw instead of returning an image (a test plugin)";
    bad.parameters = {
        statmc::bool_parameter("not_std", false, "throw an int, not a std::exception")};
    bad.run = [fail](const std::vector<const OIIO::ImageBuf*>&, const statmc::ParameterValues& p,
                     const statmc::RunContext&) -> OIIO::ImageBuf {
        fail(p);
        return {};
    };
    statmc::OperatorSpec bad_in_place = bad;
    bad_in_place.name = "testthrowinplace";
    bad_in_place.summary = "Throw from run_in_place (a test plugin)";
    bad_in_place.run_in_place = [fail](OIIO::ImageBuf&, const statmc::ParameterValues& p,
                                       const statmc::RunContext&) {
        fail(p);
        return false;
    };
    registry.add(std::move(bad));
    registry.add(std::move(bad_in_place));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_testscale)
