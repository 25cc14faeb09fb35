// denoise: the StatMC filter on a statistics image (docs/method.md §5), as a statmc plugin.
// One input (the top of the stack); pushes the image with the AOV's mean (R,G,B by
// default) denoised. The parameter table is `statmc --help denoise`, generated from
// parameters() below; every default comes from DenoiseImageOptions{}.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/strutil.h>

#include "statmc/denoise/denoise.h"
#include "statmc/layers/renderer_presets.h"
#include "statmc/layers/storage_rules.h"
#include "statmc/plugin_sdk/plugin_interface.h"

namespace {

using statmc::ParameterValues;

// The default method's options, built on first use (not at load time).
const statmc::DenoiseImageOptions& defaults()
{
    static const statmc::DenoiseImageOptions options;
    return options;
}

// Each choice's spelling beside its value, so that parsing, the choice list and the
// default's name are one table.
const std::vector<std::pair<std::string, statmc::TestDomainChoice>> kTests = {
    {"auto", statmc::TestDomainChoice::Auto},
    {"boxcox", statmc::TestDomainChoice::BoxCox},
    {"untransformed", statmc::TestDomainChoice::Untransformed},
};
// The presets a `method` names; their explicit parameters override them.
const std::vector<std::pair<std::string, statmc::Method>> kMethods = {
    {"default", statmc::Method::Default},
    {"classic", statmc::Method::Classic},
    {"paper", statmc::Method::Paper},
};
const std::vector<std::pair<std::string, statmc::Device>> kDevices = {
    {"cpu", statmc::Device::Cpu},
    {"cuda", statmc::Device::Cuda},
    {"auto", statmc::Device::Auto},
};
const std::vector<std::pair<std::string, statmc::NonfinitePolicy>> kNonfinite = {
    {"error", statmc::NonfinitePolicy::Error},
    {"zero", statmc::NonfinitePolicy::Zero},
};

template <class T>
std::vector<std::string> spellings(const std::vector<std::pair<std::string, T>>& table)
{
    std::vector<std::string> names;
    for (const auto& entry : table)
        names.push_back(entry.first);
    return names;
}

template <class T>
const std::string& spelling(const std::vector<std::pair<std::string, T>>& table, T value)
{
    return std::find_if(table.begin(), table.end(),
                        [&](const auto& e) { return e.second == value; })
        ->first;
}

// The host has checked the name against the choices already.
template <class T>
T chosen(const std::vector<std::pair<std::string, T>>& table, const std::string& name, T fallback)
{
    const auto it =
        std::find_if(table.begin(), table.end(), [&](const auto& e) { return e.first == name; });
    return it == table.end() ? fallback : it->second;
}

// "auto" uses a guide when the image has it; a list requires its guides; "none" none.
statmc::GuideUse guide_use(const std::vector<std::string>& guides, const char* guide)
{
    if (guides == std::vector<std::string>{"auto"})
        return statmc::GuideUse::Auto;
    const bool listed = std::find(guides.begin(), guides.end(), guide) != guides.end();
    return listed ? statmc::GuideUse::Required : statmc::GuideUse::Off;
}

statmc::DenoiseImageOptions options_from(const ParameterValues& p)
{
    statmc::DenoiseImageOptions opt = statmc::DenoiseImageOptions::of(
        chosen(kMethods, p.get_string("method", "default"), statmc::Method::Default));
    opt.filter.radius = p.get_int("radius", opt.filter.radius);
    opt.filter.alpha = p.get_float("alpha", opt.filter.alpha);
    opt.filter.sigma_albedo = float(p.get_float("sigma_albedo", opt.filter.sigma_albedo));
    opt.filter.sigma_normal = float(p.get_float("sigma_normal", opt.filter.sigma_normal));
    opt.filter.firefly_ratio = float(p.get_float("fireflies", opt.filter.firefly_ratio));
    const std::vector<std::string> guides = p.get_list("guides", {"auto"});
    opt.guides.albedo = guide_use(guides, "albedo");
    opt.guides.normal = guide_use(guides, "normal");
    opt.test = chosen(kTests, p.get_string("test", spelling(kTests, opt.test)), opt.test);
    opt.filter.device = chosen(
        kDevices, p.get_string("device", spelling(kDevices, opt.filter.device)), opt.filter.device);
    opt.nonfinite = chosen(
        kNonfinite, p.get_string("nonfinite", spelling(kNonfinite, opt.nonfinite)), opt.nonfinite);
    opt.from = p.get_string("from", opt.from);
    opt.aov = p.get_string("aov", opt.aov);
    if (const std::string aovs = p.get_string("aovs", ""); !aovs.empty())
        opt.aovs = OIIO::Strutil::splits(aovs, ",");
    opt.joint = p.get_bool("joint", opt.joint);
    opt.diagnostics = p.get_bool("diagnostics", opt.diagnostics);
    opt.temporal.frames = p.get_int("temporal", opt.temporal.frames);
    opt.temporal.radius = p.get_int("temporal_radius", opt.temporal.radius);
    return opt;
}

std::vector<statmc::ParameterSpec> parameters()
{
    using namespace statmc;
    const DenoiseOptions& f = defaults().filter;
    return {
        choice_parameter("method", spellings(kMethods), "default",
                         "default: the classic filter with each pixel at its own radius (the "
                         "ICI ladder and its energy and residual checks, left out with a note "
                         "on a file without the variance layer) and the context test "
                         "(docs/method.md §11, §16, §17); classic: the 2024 "
                         "filter with the firefly guard; paper: Sakai et al. 2024 bit for bit. "
                         "The parameters below apply over any method"),
        int_parameter("radius", f.radius, "filter disk radius in pixels").between(0, 1000),
        float_parameter("alpha", f.alpha, "significance level of the t-test").open_between(0, 1),
        float_parameter("sigma_albedo", f.sigma_albedo, "albedo guide falloff").above(0),
        float_parameter("sigma_normal", f.sigma_normal, "normal guide falloff").above(0),
        float_parameter("fireflies", std::nullopt,
                        "firefly guard: no pixel averages a neighbour whose noise level (the "
                        "Box-Cox sample variance, or s^2/mean for the untransformed test) "
                        "exceeds this many times its own "
                        "(halos of highlights, fireflies); 0 = off, else at least 1. Default and "
                        "classic " +
                            number_text(f.firefly_ratio) + ", paper 0")
            .at_least(0),
        list_parameter("guides", {"albedo", "normal"}, {"auto", "none"}, "auto",
                       "guide layers: a list is required to be present, auto uses those "
                       "present, none none"),
        choice_parameter("test", spellings(kTests), spelling(kTests, defaults().test),
                         "test domain: auto = boxcox when the Box-Cox layers are present, "
                         "else untransformed"),
        choice_parameter("device", spellings(kDevices),
                         spelling(kDevices, defaults().filter.device),
                         "where the filter kernel runs: cpu (the reference bits), cuda (a CUDA "
                         "GPU: the same members, values within float summation order; an error "
                         "where none is present), auto (a GPU when present and the image has at "
                         "least 512x512 pixels) (docs/gpu.md)"),
        choice_parameter("nonfinite", spellings(kNonfinite),
                         spelling(kNonfinite, defaults().nonfinite),
                         "NaN/Inf in the statistics: error refuses the image, zero counts "
                         "them as 0"),
        choice_parameter("from", layers::renderer_preset_choices(), defaults().from,
                         "whose channel names the image has: auto recognises statmc's own, "
                         "RenderMan's (mse, sampleCount), pbrt-v4's gbuffer (Variance, "
                         "samplesPerPixel) and Blender Cycles' (ViewLayer.Combined; passes "
                         "only) and refuses an ambiguous image; or name one "
                         "(docs/renderers.md)"),
        string_parameter("aov", defaults().aov,
                         "the AOV whose mean is denoised (docs/exr-layers.md), e.g. diffuse or "
                         "bounce1L; empty: the beauty R,G,B"),
        string_parameter("aovs", "",
                         "more AOVs denoised beside aov, comma-separated (e.g. "
                         "diffuse,specular); each by its own test unless joint")
            .written_as("name,name,..."),
        bool_parameter("joint", defaults().joint,
                       "with aovs: average every listed AOV with aov's members and weights, so "
                       "that AOVs summing to the beauty still sum to the denoised beauty; the "
                       "membership is every AOV's test where each has its statistics, else "
                       "aov's (docs/method.md §14). Leaves the ICI ladder out"),
        int_parameter("temporal", defaults().temporal.frames,
                      "frame sequences: merge the members that the K frames before and after "
                      "offer (a pixel of another frame joins when the t-test cannot tell it "
                      "from this one, following motion.X/Y when every frame has it; "
                      "docs/method.md §13). Cut at the sequence's ends; 0 = off")
            .between(0, 16),
        int_parameter("temporal_radius", defaults().temporal.radius,
                      "with temporal: also offer the pixels within this radius of the "
                      "corresponding pixel in each other frame; 0 = that pixel only")
            .between(0, 8),
        bool_parameter("diagnostics", defaults().diagnostics,
                       "add [<aov>.]diagnostics.members and .effectiveSamples: per pixel, the "
                       "pixels averaged and the effective sample count (Σw)²/Σ(w²/n)"),
    };
}

// One line about the input, to the host's message sink: "--denoise: note: in.exr: ...".
void tell(const char* kind, const statmc::RunContext& ctx, const std::string& text)
{
    const std::string label = ctx.input_labels.empty() ? "" : ctx.input_labels[0] + ": ";
    ctx.tell("--denoise: " + std::string(kind) + ": " + label + text);
}

// The user learns once, on stderr, that the method ran without one of its stages.
void note_skipped_stages(const OIIO::ImageBuf& result, const statmc::RunContext& ctx)
{
    const std::string skipped =
        result.spec().get_string_attribute(statmc::layers::attr::kDenoiseSkipped);
    if (!skipped.empty() && !result.has_error())
        tell("note", ctx, "left out " + skipped);
}

// A denoised layer keeps its statistics but not its mean: denoised again, it is tested
// against statistics of samples it no longer is the mean of. Another layer of the file
// (aov=) is still as rendered, so this warns, and only about layers denoised before.
void warn_denoised_input(const OIIO::ImageBuf& input, const statmc::DenoiseImageOptions& opt,
                         const statmc::RunContext& ctx)
{
    const OIIO::ImageSpec& spec = input.spec();
    if (spec.get_int_attribute(statmc::layers::attr::kDenoised, 0) != 1)
        return;
    // Files from before statmc:denoisedLayers say only that something was denoised.
    const std::string done = spec.get_string_attribute(statmc::layers::attr::kDenoisedLayers);
    std::vector<std::string> asked = {opt.aov.empty() ? std::string("beauty") : opt.aov};
    asked.insert(asked.end(), opt.aovs.begin(), opt.aovs.end());
    for (const std::string& layer : asked)
        if (done.empty() || ("," + done + ",").find("," + layer + ",") != std::string::npos) {
            tell("warning", ctx,
                 (done.empty()
                      ? std::string("denoised already (statmc:denoised = 1)")
                      : layer + " denoised already (statmc:denoisedLayers = " + done + ")") +
                     ": what was denoised is no longer its samples' mean; denoise the "
                     "statistics it came from");
            return;
        }
}

// Statistics stored under lossy compression carry its rounding in every moment: the
// result is still computed, but the user should know the file breaks the contract.
void note_lossy_storage(const OIIO::ImageBuf& input, const statmc::RunContext& ctx)
{
    const std::string compression = input.spec().get_string_attribute("compression");
    if (compression.empty() || statmc::layers::is_lossless_compression(compression))
        return;
    tell("warning", ctx,
         "statistics stored with lossy compression '" + compression +
             "': their variances and moments carry its rounding (the layer contract stores "
             "them lossless)");
}

// The neighbours the host can lend, up to `reach` on each side; a sequence needed and not
// given is an error before any work.
statmc::FrameNeighbours neighbours_from(const statmc::RunContext& ctx, int reach)
{
    statmc::FrameNeighbours neighbours;
    if (reach == 0)
        return neighbours;
    if (!ctx.sequence_frames)
        throw std::invalid_argument(
            "temporal=" + std::to_string(reach) +
            " needs a frame sequence: read the input with a frame pattern (shot.#.exr, "
            "shot.%04d.exr) and denoise it as read, e.g. statmc shot.#.exr --frames 1-48 "
            "--denoise:temporal=" +
            std::to_string(reach) + " -o out.#.exr");
    std::vector<int> offsets;
    for (int k = 1; k <= reach; ++k)
        offsets.insert(offsets.end(), {-k, k});
    const std::vector<const OIIO::ImageBuf*> frames = ctx.sequence_frames(offsets);
    // Nearest first on each side, up to the sequence's end.
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        std::vector<const OIIO::ImageBuf*>& side =
            offsets[i] < 0 ? neighbours.previous : neighbours.next;
        if (frames[i] && int(side.size()) == std::abs(offsets[i]) - 1)
            side.push_back(frames[i]);
    }
    return neighbours;
}

// How the result was made, as the command line spells it: the method, then every
// parameter given, in the table's order ("method=default:radius=8:guides=albedo").
std::string settings_text(const ParameterValues& p)
{
    std::string text = "method=" + p.get_string("method", "default");
    for (const statmc::ParameterSpec& spec : parameters())
        if (spec.name != "method" && p.has(spec.name))
            text += ":" + spec.name + "=" + p.text(spec.name);
    return text;
}

// The header of a denoised image says how it was made and by which statmc.
void record_settings(OIIO::ImageBuf& result, const ParameterValues& p)
{
    if (result.has_error())
        return;
    result.specmod().attribute(statmc::layers::attr::kDenoiseSettings, settings_text(p));
    result.specmod().attribute(statmc::layers::attr::kVersion, STATMC_VERSION);
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
    op.check = [](const ParameterValues& p) -> std::string { return options_from(p).validate(); };
    op.run = [](const std::vector<const OIIO::ImageBuf*>& inputs, const ParameterValues& p,
                const statmc::RunContext& ctx) {
        note_lossy_storage(*inputs[0], ctx);
        const statmc::DenoiseImageOptions opt = options_from(p);
        warn_denoised_input(*inputs[0], opt, ctx);
        OIIO::ImageBuf result;
        try {
            result = statmc::denoise(*inputs[0], neighbours_from(ctx, opt.temporal.frames), opt, {},
                                     ctx.nthreads);
        } catch (const std::exception& e) {
            result.errorfmt("denoise: {}", e.what());
        }
        note_skipped_stages(result, ctx);
        record_settings(result, p);
        return result;
    };
    op.run_in_place = [](OIIO::ImageBuf& image, const ParameterValues& p,
                         const statmc::RunContext& ctx) {
        note_lossy_storage(image, ctx);
        const statmc::DenoiseImageOptions opt = options_from(p);
        warn_denoised_input(image, opt, ctx);
        bool ok = false;
        try {
            ok = statmc::denoise(image, image, neighbours_from(ctx, opt.temporal.frames), opt, {},
                                 ctx.nthreads);
        } catch (const std::exception& e) {
            image.errorfmt("denoise: {}", e.what());
        }
        if (ok) {
            note_skipped_stages(image, ctx);
            record_settings(image, p);
        }
        return ok;
    };
    registry.add(std::move(op));
}

}  // namespace

STATMC_EXPORT_PLUGIN(register_denoise)
