// --denoise: the denoise operator on the top image.
#include <algorithm>

#include "statmc/denoise/denoise.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/tool_context.h"
#include "statmc/tool/tool_error.h"

namespace statmc::tool {

namespace {

bool listed(const std::vector<std::string>& items, const char* item)
{
    return std::find(items.begin(), items.end(), item) != items.end();
}

// "auto" uses a guide when the image has it; a list requires its guides; "none" none.
GuideUse guide_use(const std::vector<std::string>& guides, const char* guide)
{
    if (guides == std::vector<std::string>{"auto"})
        return GuideUse::Auto;
    return listed(guides, guide) ? GuideUse::Required : GuideUse::Off;
}

TestDomainChoice test_choice(const std::string& name)
{
    if (name == "boxcox")
        return TestDomainChoice::BoxCox;
    if (name == "untransformed")
        return TestDomainChoice::Untransformed;
    return TestDomainChoice::Auto;
}

DenoiseImageOptions denoise_options(const Invocation& inv)
{
    const Modifiers& m = inv.modifiers;
    DenoiseImageOptions opt;
    opt.filter.radius = m.get_int("radius");
    opt.filter.alpha = m.get_float("alpha");
    opt.filter.sigma_spatial = float(m.get_float("sigma_s"));
    opt.filter.sigma_albedo = float(m.get_float("sigma_albedo"));
    opt.filter.sigma_normal = float(m.get_float("sigma_normal"));
    opt.guides.albedo = guide_use(m.get_list("guides"), "albedo");
    opt.guides.normal = guide_use(m.get_list("guides"), "normal");
    opt.guides.albedo_layer = m.get_string("albedo_layer");
    opt.guides.normal_layer = m.get_string("normal_layer");
    opt.test = test_choice(m.get_string("test"));
    opt.nonfinite = m.get_string("nonfinite") == "zero" ? NonfinitePolicy::Zero
                                                        : NonfinitePolicy::Error;
    if (const std::string why = opt.validate(); !why.empty())
        throw ToolError(inv.name + ": " + why);
    return opt;
}

std::vector<ModifierSpec> denoise_modifiers()
{
    using T = ModifierType;
    return {
        {"radius", T::Int, "20", "filter disk radius in pixels, in [0, 1000]", {}, {}},
        {"alpha", T::Float, "0.005", "significance level of the t-test, in (0, 1)", {}, {}},
        {"sigma_s", T::Float, "10", "spatial Gaussian falloff in pixels, > 0", {}, {}},
        {"sigma_albedo", T::Float, "0.02", "albedo guide falloff, > 0", {}, {}},
        {"sigma_normal", T::Float, "0.1", "normal guide falloff, > 0", {}, {}},
        {"guides", T::List, "auto",
         "guide layers: a list is required to be present, auto uses those present, none none",
         {"albedo", "normal"}, {"auto", "none"}},
        {"albedo_layer", T::String, "albedo", "layer of the albedo guide (.R,.G,.B)", {}, {}},
        {"normal_layer", T::String, "normal", "layer of the normal guide (.X,.Y,.Z)", {}, {}},
        {"test", T::Choice, "auto",
         "test domain: auto = boxcox when the Box-Cox layers are present, else untransformed",
         {"auto", "boxcox", "untransformed"}, {}},
        {"nonfinite", T::Choice, "error",
         "NaN/Inf in the statistics: error refuses the image, zero counts them as 0",
         {"error", "zero"}, {}},
    };
}

}  // namespace

Command denoise_command()
{
    Command c;
    c.name = "--denoise";
    c.summary = "Denoise the top image (a statistics image): R,G,B replaced, all else kept";
    c.modifiers = denoise_modifiers();
    c.check = [](const Invocation& inv) { denoise_options(inv); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const DenoiseImageOptions opt = denoise_options(inv);
        StackImage src = ctx.stack.pop(inv.name);
        StackImage result{OIIO::ImageBuf(), src.label + " (denoised)"};
        if (!statmc::denoise(result.image, src.image, opt, {}, ctx.nthreads))
            throw ToolError(inv.name + ": " + src.label + ": " + result.image.geterror());
        ctx.stack.push(std::move(result));
    };
    return c;
}

}  // namespace statmc::tool
