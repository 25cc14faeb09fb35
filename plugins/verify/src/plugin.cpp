// verify: another denoiser's output held to the pixels' own statistics (docs/method.md
// §15), as a statmc plugin. Pops the candidate (top) and the statistics image below it;
// pushes the statistics image with the verified beauty and diagnostics.rejected. The
// parameter table is `statmc --help verify`, generated from the specs below.
#include <iomanip>
#include <string>

#include "statmc/layers/layer_names.h"
#include "statmc/plugin_sdk/plugin_interface.h"
#include "statmc/verify/verify.h"

namespace {

const statmc::VerifyOptions kDefaults{};

OIIO::ImageBuf run(const std::vector<const OIIO::ImageBuf*>& inputs,
                   const statmc::ParameterValues& p, const statmc::RunContext& ctx)
{
    statmc::VerifyOptions opt;
    opt.test.alpha = p.get_float("alpha", opt.test.alpha);
    opt.test.box_radius = p.get_int("box", opt.test.box_radius);
    opt.candidate_layer = p.get_string("candidate", opt.candidate_layer);
    opt.fallback = p.get_string("fallback", "denoise") == "mean" ? statmc::VerifyFallback::Mean
                                                                 : statmc::VerifyFallback::Denoise;
    OIIO::ImageBuf out = statmc::verify(*inputs[0], *inputs[1], opt, {}, ctx.nthreads);
    if (!out.has_error() && ctx.out) {
        const float share =
            out.spec().get_float_attribute(statmc::layers::attr::kVerifyRejected, 0.f);
        *ctx.out << "verify: " << ctx.input_labels.at(1) << " rejected at " << std::setprecision(3)
                 << 100.0 * share << "% of the pixels of " << ctx.input_labels.at(0) << "\n";
    }
    return out;
}

void register_verify(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "verify";
    op.summary = "Keep a denoiser's output (top) where the statistics image below it cannot "
                 "reject it; statmc's estimate elsewhere";
    op.help = "Per pixel and channel, the candidate c is tested against the pixel's mean: "
              "|mean - c| beyond the Student-t critical value times the standard error "
              "sqrt(v/n), v the moderated variance of the default method, df = n - 1 + 16; "
              "and the same for the mean difference over the (2 box + 1)^2 pixels around it "
              "(Welch-Satterthwaite df). A correct candidate is rejected at a pixel with "
              "probability at most alpha. With the default fallback a rejected candidate is "
              "tested again with the default --denoise's estimate in place of the mean, and "
              "takes that estimate only where this test rejects it too (with "
              "fallback=mean: its own mean); diagnostics.rejected maps the pixels replaced "
              "(1 pixel, 2 box, 3 both). "
              "Candidate and statistics must cover one data window. Chain a denoiser with "
              "--dup: statmc f.exr --dup --oidn --verify -o out.exr";
    op.parameters = {
        statmc::float_parameter("alpha", kDefaults.test.alpha,
                                "chance that a correct candidate is rejected at a pixel")
            .open_between(0, 1),
        statmc::int_parameter("box", kDefaults.test.box_radius,
                              "radius of the box whose mean difference is tested too; 0: the "
                              "pixel alone")
            .between(0, 8),
        statmc::string_parameter("candidate", kDefaults.candidate_layer,
                                 "the candidate's layer (default: its R,G,B)"),
        statmc::choice_parameter("fallback", {"denoise", "mean"}, "denoise",
                                 "what a rejected pixel takes: the default --denoise, or its "
                                 "own noisy mean"),
    };
    op.inputs = 2;
    op.run = run;
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_verify)
