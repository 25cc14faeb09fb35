// oidn: Intel Open Image Denoise on the beauty, loaded at run time, as a statmc plugin:
// a candidate for --verify (docs/method.md §15). One input; pushes the image with its
// beauty denoised. The parameter table is `statmc --help oidn`.
#include "statmc/oidn/oidn.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

OIIO::ImageBuf run(const std::vector<const OIIO::ImageBuf*>& inputs,
                   const statmc::ParameterValues& p, const statmc::RunContext& ctx)
{
    statmc::OidnOptions opt;
    opt.guides = p.get_bool("guides", opt.guides);
    opt.library = p.get_string("library", opt.library);
    return statmc::oidn_denoise(*inputs[0], opt, ctx.nthreads);
}

void register_oidn(statmc::PluginRegistry& registry)
{
    const statmc::OidnOptions defaults;
    statmc::OperatorSpec op;
    op.name = "oidn";
    op.summary = "Denoise the beauty with Intel Open Image Denoise (optional; a candidate for "
                 "--verify)";
    op.help = "OIDN 2's RT filter on the CPU, in HDR mode, with the albedo and normal layers "
              "when present. OIDN is loaded at run time from " +
              statmc::oidn_library_search_text() +
              "; get it with `python3 -m pip install pyoidn`. Its output is not held to the "
              "samples: chain --verify for that (statmc f.exr --dup --oidn --verify).";
    op.parameters = {
        statmc::bool_parameter("guides", defaults.guides,
                               "give OIDN the albedo and normal layers when present"),
        statmc::string_parameter("library", defaults.library,
                                 "the OIDN library to load (default: searched)")
            .written_as("file"),
    };
    op.run = run;
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_oidn)
