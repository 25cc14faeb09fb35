// denoise: the StatMC filter on a statistics image (docs/method.md §5), as a statmc plugin.
//
// | parameter    | type   | default | range     | meaning                                     |
// |--------------|--------|---------|-----------|---------------------------------------------|
// | radius       | int    | 20      | [0, 1000] | filter disk radius in pixels                |
// | alpha        | float  | 0.005   | (0, 1)    | significance level of the t-test            |
// | sigma_s      | float  | 10      | > 0       | spatial Gaussian falloff in pixels          |
// | sigma_albedo | float  | 0.02    | > 0       | albedo guide falloff                        |
// | sigma_normal | float  | 0.1     | > 0       | normal guide falloff                        |
// | fireflies    | float  | 256     | 0 or >= 1 | firefly guard variance ratio; 0 = paper's   |
// | guides       | list   | auto    |           | albedo,normal (required) / auto / none      |
// | albedo_layer | string | albedo  |           | layer of the albedo guide                   |
// | normal_layer | string | normal  |           | layer of the normal guide                   |
// | test         | choice | auto    |           | auto / boxcox / untransformed               |
// | nonfinite    | choice | error   |           | NaN/Inf: refuse the image, or count as 0    |
// | aov          | string | (empty) |           | AOV denoised, e.g. diffuse, bounce1L; empty = R,G,B |
// | diagnostics  | bool   | 0       |           | add diagnostics.members/.effectiveSamples   |
//
// One input (the top of the stack); pushes the image with the AOV's mean (R,G,B by
// default) denoised.
#include <algorithm>

#include "statmc/denoise/denoise.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

using statmc::ParameterValues;

// "auto" uses a guide when the image has it; a list requires its guides; "none" none.
statmc::GuideUse guide_use(const std::vector<std::string>& guides, const char* guide)
{
    if (guides == std::vector<std::string>{"auto"})
        return statmc::GuideUse::Auto;
    const bool listed = std::find(guides.begin(), guides.end(), guide) != guides.end();
    return listed ? statmc::GuideUse::Required : statmc::GuideUse::Off;
}

statmc::TestDomainChoice test_choice(const std::string& name)
{
    if (name == "boxcox")
        return statmc::TestDomainChoice::BoxCox;
    if (name == "untransformed")
        return statmc::TestDomainChoice::Untransformed;
    return statmc::TestDomainChoice::Auto;
}

statmc::DenoiseImageOptions options_from(const ParameterValues& p)
{
    statmc::DenoiseImageOptions opt;
    opt.filter.radius = p.get_int("radius", opt.filter.radius);
    opt.filter.alpha = p.get_float("alpha", opt.filter.alpha);
    opt.filter.sigma_spatial = float(p.get_float("sigma_s", opt.filter.sigma_spatial));
    opt.filter.sigma_albedo = float(p.get_float("sigma_albedo", opt.filter.sigma_albedo));
    opt.filter.sigma_normal = float(p.get_float("sigma_normal", opt.filter.sigma_normal));
    opt.filter.firefly_ratio = float(p.get_float("fireflies", opt.filter.firefly_ratio));
    const std::vector<std::string> guides = p.get_list("guides", {"auto"});
    opt.guides.albedo = guide_use(guides, "albedo");
    opt.guides.normal = guide_use(guides, "normal");
    opt.guides.albedo_layer = p.get_string("albedo_layer", opt.guides.albedo_layer);
    opt.guides.normal_layer = p.get_string("normal_layer", opt.guides.normal_layer);
    opt.test = test_choice(p.get_string("test", "auto"));
    opt.nonfinite = p.get_string("nonfinite", "error") == "zero" ? statmc::NonfinitePolicy::Zero
                                                                 : statmc::NonfinitePolicy::Error;
    opt.aov = p.get_string("aov", "");
    opt.diagnostics = p.get_bool("diagnostics", false);
    return opt;
}

std::vector<statmc::ParameterSpec> parameters()
{
    using namespace statmc;
    return {
        int_parameter("radius", 20, "filter disk radius in pixels").between(0, 1000),
        float_parameter("alpha", 0.005, "significance level of the t-test").open_between(0, 1),
        float_parameter("sigma_s", 10, "spatial Gaussian falloff in pixels").above(0),
        float_parameter("sigma_albedo", 0.02, "albedo guide falloff").above(0),
        float_parameter("sigma_normal", 0.1, "normal guide falloff").above(0),
        float_parameter("fireflies", 256,
                        "firefly guard (Box-Cox test only): no pixel averages a neighbour "
                        "whose sample variance exceeds this many times its own noise level "
                        "(halos of highlights, fireflies); 0 = the paper's filter").at_least(0),
        list_parameter("guides", {"albedo", "normal"}, {"auto", "none"}, "auto",
                       "guide layers: a list is required to be present, auto uses those "
                       "present, none none"),
        string_parameter("albedo_layer", "albedo", "layer of the albedo guide (.R,.G,.B)"),
        string_parameter("normal_layer", "normal", "layer of the normal guide (.X,.Y,.Z)"),
        choice_parameter("test", {"auto", "boxcox", "untransformed"}, "auto",
                         "test domain: auto = boxcox when the Box-Cox layers are present, "
                         "else untransformed"),
        choice_parameter("nonfinite", {"error", "zero"}, "error",
                         "NaN/Inf in the statistics: error refuses the image, zero counts "
                         "them as 0"),
        string_parameter("aov", "",
                         "the AOV whose mean is denoised (docs/exr-layers.md), e.g. diffuse or "
                         "bounce1L; empty: the beauty R,G,B"),
        bool_parameter("diagnostics", false,
                       "add [<aov>.]diagnostics.members and .effectiveSamples: per pixel, the "
                       "pixels averaged and the effective sample count (Σw)²/Σ(w²/n)"),
    };
}

void register_denoise(statmc::PluginRegistry& registry)
{
    statmc::OperatorSpec op;
    op.name = "denoise";
    op.summary = "Denoise the top image (a statistics image): R,G,B replaced, all else kept";
    op.help = "Averages each pixel with the neighbours whose expectations a Student-t test "
              "cannot tell apart (Sakai et al. 2024). Reads the mean, sampleCount and "
              "variance or Box-Cox layers (docs/exr-layers.md); sets statmc:denoised=1.";
    op.parameters = parameters();
    op.check = [](const ParameterValues& p) { return options_from(p).validate(); };
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const ParameterValues& p,
                const statmc::RunContext& ctx) {
        return statmc::denoise(*inputs[0], options_from(p), {}, ctx.nthreads);
    };
    op.run_in_place = [](OIIO::ImageBuf& image, const ParameterValues& p, const statmc::RunContext& ctx) {
        return statmc::denoise(image, image, options_from(p), {}, ctx.nthreads);
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_denoise)
