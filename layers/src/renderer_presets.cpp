#include "statmc/layers/renderer_presets.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <set>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/strutil.h>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"

namespace statmc::layers {

namespace {

// Render: the beauty, alpha and guides, which --passes reads too. Statistic: what only the
// statistics route reads.
enum class Role { Render, Statistic };

// One contract layer and the renderer's spellings of it, in order of preference; each
// alternative names one source channel per contract channel. "{L}" stands for the view
// layer of a Blender multilayer file.
struct Rule {
    Role role;
    bool required;
    std::vector<std::string> contract;
    std::vector<std::vector<std::string>> sources;
};

// The channel names and header of one renderer, with the source of every name in
// docs/renderers.md.
struct Preset {
    const char* name;
    const char* renderer;
    std::string (*evidence)(const OIIO::ImageSpec& spec);
    std::vector<Rule> rules;
    const char* variance_of;      // kVarianceOfSample or kVarianceOfMean; null: no statistics
    const char* count_attribute;  // an int header attribute holding every pixel's count
    const char* no_statistics;    // why the statistics route is closed, and what to do
    // Light groups: "<prefix><group>.<channel>" becomes the AOV "<group>.<channel>" on the
    // render route (Cycles' "{L}.Combined_<group>.R"); null: none.
    const char* light_group_prefix = nullptr;
};

// {prefix + "." + s for s in suffixes}, "" prefix = the bare suffixes.
std::vector<std::string> named(const std::string& prefix, std::vector<std::string> suffixes)
{
    if (!prefix.empty())
        for (std::string& s : suffixes)
            s = prefix + "." + s;
    return suffixes;
}

const std::vector<std::string> kRgb = {"R", "G", "B"};
const std::vector<std::string> kLowerRgb = {"r", "g", "b"};
const std::vector<std::string> kXyz = {"X", "Y", "Z"};
const std::vector<std::string> kLowerXyz = {"x", "y", "z"};

bool has_channel(const OIIO::ImageSpec& spec, const std::string& name)
{
    return spec.channelindex(name) >= 0;
}

const char* const kCyclesBeauties[] = {".Noisy Image.R", ".Combined.R"};

// The view layers of a Blender multilayer file: L of every "L.Combined.R" or
// "L.Noisy Image.R".
std::set<std::string> view_layers(const OIIO::ImageSpec& spec)
{
    std::set<std::string> found;
    for (const std::string& channel : spec.channelnames)
        for (const char* beauty : kCyclesBeauties)
            if (OIIO::Strutil::ends_with(channel, beauty) && channel.size() > std::strlen(beauty))
                found.insert(channel.substr(0, channel.size() - std::strlen(beauty)));
    return found;
}

// The evidence that `spec` is in statmc's own contract or one renderer's names (a channel
// or attribute only it writes), "" when there is none.
std::string contract_evidence(const OIIO::ImageSpec& spec)
{
    if (has_channel(spec, kSampleCountChannel))
        return std::string("channel ") + kSampleCountChannel;
    return spec.find_attribute(attr::kFormatVersion)
               ? std::string("attribute ") + attr::kFormatVersion
               : "";
}

std::string renderman_evidence(const OIIO::ImageSpec& spec)
{
    for (const std::string& channel : spec.channelnames)
        if (channel == "mse" || OIIO::Strutil::starts_with(channel, "mse."))
            return "channel " + channel;
    return "";
}

std::string pbrt_v4_evidence(const OIIO::ImageSpec& spec)
{
    if (has_channel(spec, "RelativeVariance.R"))
        return "channel RelativeVariance.R";
    return has_channel(spec, "Variance.R") && spec.find_attribute("samplesPerPixel")
               ? "channel Variance.R and attribute samplesPerPixel"
               : "";
}

// Only the multilayer names: a single-layer Blender EXR is a plain R,G,B render, although
// its header has cycles.<view layer>.samples too.
std::string cycles_evidence(const OIIO::ImageSpec& spec)
{
    const std::set<std::string> layers = view_layers(spec);
    for (const char* beauty : kCyclesBeauties)
        for (const std::string& layer : layers)
            if (has_channel(spec, layer + beauty))
                return "channel " + layer + beauty;
    return "";
}

// RenderMan writes colour AOVs as .r/.g/.b; files passed through other tools often come
// back upper-case, so both spellings are taken.
std::vector<std::vector<std::string>> renderman_colour(const std::string& layer)
{
    return {named(layer, kLowerRgb), named(layer, kRgb)};
}

Rule renderman_aov(const std::string& aov, Role role, const std::string& source)
{
    return {role, false, named(aov, kRgb), renderman_colour(source)};
}

const std::vector<Preset>& presets()
{
    static const std::vector<Preset> table = {
        {"renderman",
         "Pixar RenderMan 24-26 (denoiser AOVs)",
         &renderman_evidence,
         {
             {Role::Render, true, kRgb, {kRgb, named("Ci", kLowerRgb), named("Ci", kRgb)}},
             {Role::Render, false, {"A"}, {{"A"}, {"a"}, {"Ci.a"}}},
             {Role::Statistic, true, named("variance", kRgb), renderman_colour("mse")},
             {Role::Statistic,
              true,
              {kSampleCountChannel},
              {{"sampleCount"}, {"sampleCount.Y"}, {"sampleCount.r"}, {"sampleCount.R"}}},
             {Role::Render, false, named(kAlbedoLayer, kRgb), renderman_colour("albedo")},
             {Role::Render,
              false,
              named(kNormalLayer, kXyz),
              {named("normal", kLowerXyz), named("normal", kXyz), named("normal", kLowerRgb),
               named("normal", kRgb)}},
             renderman_aov("diffuse", Role::Statistic, "diffuse"),
             renderman_aov("diffuse.variance", Role::Statistic, "diffuse_mse"),
             renderman_aov("specular", Role::Statistic, "specular"),
             renderman_aov("specular.variance", Role::Statistic, "specular_mse"),
         },
         kVarianceOfMean,
         nullptr,
         nullptr},
        {"pbrt-v4",
         "pbrt-v4 (GBufferFilm)",
         &pbrt_v4_evidence,
         {
             {Role::Render, true, kRgb, {kRgb}},
             {Role::Statistic, true, named("variance", kRgb), {named("Variance", kRgb)}},
             {Role::Render, false, named(kAlbedoLayer, kRgb), {named("Albedo", kRgb)}},
             {Role::Render,
              false,
              named(kNormalLayer, kXyz),
              {named("Ns", kXyz), {"Nsx", "Nsy", "Nsz"}}},
         },
         kVarianceOfSample,
         "samplesPerPixel",
         nullptr},
        {"cycles",
         "Blender Cycles (multilayer EXR)",
         &cycles_evidence,
         {
             {Role::Render,
              true,
              kRgb,
              {named("{L}.Noisy Image", kRgb), named("{L}.Combined", kRgb)}},
             {Role::Render, false, {"A"}, {{"{L}.Noisy Image.A"}, {"{L}.Combined.A"}}},
             {Role::Render,
              false,
              named(kAlbedoLayer, kRgb),
              {named("{L}.Denoising Albedo", kRgb)}},
             {Role::Render,
              false,
              named(kNormalLayer, kXyz),
              {named("{L}.Denoising Normal", kXyz)}},
             {Role::Render, false, {std::string(kDepthLayer) + ".Z"}, {{"{L}.Denoising Depth.Z"}}},
         },
         nullptr,
         nullptr,
         "Cycles writes no per-pixel variance: render K >= 2 passes with different seeds "
         "and combine them (statmc p1.exr p2.exr p3.exr p4.exr --passes --denoise -o out.exr; "
         "docs/renderers.md)",
         "{L}.Combined_"},
    };
    return table;
}

const Preset* find_preset(const std::string& name)
{
    for (const Preset& p : presets())
        if (name == p.name)
            return &p;
    return nullptr;
}

std::string source_name(const std::string& pattern, const std::string& view_layer)
{
    return OIIO::Strutil::replace(pattern, "{L}", view_layer, true);
}

std::string the_view_layer(const OIIO::ImageSpec& spec)
{
    const std::set<std::string> layers = view_layers(spec);
    if (layers.size() > 1)
        throw LayerError("the image holds view layers " + OIIO::Strutil::join(layers, ", ") +
                         "; keep the channels of one with --ch (docs/renderers.md)");
    return layers.empty() ? "ViewLayer" : *layers.begin();
}

// The first alternative of `rule` present in full, resolved to channel names; nullopt
// when none is.
std::optional<std::vector<std::string>> found_sources(const OIIO::ImageSpec& spec, const Rule& rule,
                                                      const std::string& view_layer)
{
    for (const std::vector<std::string>& alternative : rule.sources) {
        std::vector<std::string> names;
        for (const std::string& pattern : alternative)
            names.push_back(source_name(pattern, view_layer));
        if (std::all_of(names.begin(), names.end(),
                        [&](const std::string& n) { return has_channel(spec, n); }))
            return names;
    }
    return std::nullopt;
}

// A light group's channel under its AOV's name ("ViewLayer.Combined_key.R" → "key.R"),
// or `channel` itself.
std::string light_group_channel(const std::string& channel, const Preset& preset,
                                const std::string& view_layer)
{
    if (!preset.light_group_prefix)
        return channel;
    const std::string prefix = source_name(preset.light_group_prefix, view_layer);
    if (!OIIO::Strutil::starts_with(channel, prefix))
        return channel;
    const std::string rest = channel.substr(prefix.size());
    const std::size_t dot = rest.rfind('.');
    return dot != std::string::npos && is_valid_aov_name(rest.substr(0, dot)) ? rest : channel;
}

ImportedImage import_image(const OIIO::ImageBuf& src, const Preset& preset, bool statistics)
{
    const OIIO::ImageSpec& spec = src.spec();
    const std::string view_layer = the_view_layer(spec);
    std::vector<int> order;
    std::vector<float> values;
    std::vector<std::string> names, missing;
    ImportedImage out;
    std::set<int> used;
    for (const Rule& rule : preset.rules) {
        if (!statistics && rule.role == Role::Statistic)
            continue;
        const auto sources = found_sources(spec, rule, view_layer);
        if (!sources) {
            if (rule.required) {
                std::vector<std::string> first;
                for (const std::string& pattern : rule.sources.front())
                    first.push_back(source_name(pattern, view_layer));
                missing.push_back("channels " + OIIO::Strutil::join(first, ", "));
            }
            continue;
        }
        for (std::size_t c = 0; c < sources->size(); ++c) {
            const int index = spec.channelindex((*sources)[c]);
            order.push_back(index);
            values.push_back(0.0f);
            names.push_back(rule.contract[c]);
            used.insert(index);
            out.renamed.emplace_back(rule.contract[c], (*sources)[c]);
        }
    }
    if (statistics && preset.count_attribute) {
        const int count = spec.get_int_attribute(preset.count_attribute, 0);
        if (count < 1) {
            missing.push_back(std::string("header attribute ") + preset.count_attribute +
                              " (the samples per pixel, an int >= 1)");
        } else {
            order.push_back(-1);
            values.push_back(float(count));
            names.push_back(kSampleCountChannel);
        }
    }
    if (!missing.empty())
        throw LayerError(std::string("a ") + preset.renderer + " file (from=" + preset.name +
                         ") needs " + OIIO::Strutil::join(missing, "; ") +
                         "; the image has layers " + OIIO::Strutil::join(layers_in(spec), ", ") +
                         " (docs/renderers.md)");
    if (!statistics)
        for (int c = 0; c < spec.nchannels; ++c)
            if (!used.count(c)) {
                order.push_back(c);
                values.push_back(0.0f);
                names.push_back(light_group_channel(spec.channelnames[c], preset, view_layer));
                if (names.back() != spec.channelnames[c])
                    out.renamed.emplace_back(names.back(), spec.channelnames[c]);
            }
    if (!OIIO::ImageBufAlgo::channels(out.image, src, int(order.size()), order, values, names))
        throw LayerError("importing the " + std::string(preset.renderer) +
                         " channels: " + out.image.geterror());
    if (statistics)
        out.image.specmod().attribute(attr::kVariance, preset.variance_of);
    return out;
}

const Preset& named_preset(const std::string& name)
{
    if (const Preset* p = find_preset(name))
        return *p;
    throw LayerError("no renderer preset '" + name +
                     "' (presets: " + OIIO::Strutil::join(renderer_preset_names(), ", ") + ")");
}

}  // namespace

const std::vector<std::string>& renderer_preset_names()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n = {"statmc"};
        for (const Preset& p : presets())
            n.push_back(p.name);
        return n;
    }();
    return names;
}

const std::vector<std::string>& renderer_preset_choices()
{
    static const std::vector<std::string> choices = [] {
        std::vector<std::string> c = {"auto"};
        c.insert(c.end(), renderer_preset_names().begin(), renderer_preset_names().end());
        return c;
    }();
    return choices;
}

RendererMatch detect_renderer(const OIIO::ImageSpec& spec)
{
    if (std::string evidence = contract_evidence(spec); !evidence.empty())
        return {"statmc", evidence};
    std::vector<RendererMatch> matches;
    for (const Preset& p : presets())
        if (std::string evidence = p.evidence(spec); !evidence.empty())
            matches.push_back({p.name, evidence});
    if (matches.size() > 1) {
        std::vector<std::string> each;
        for (const RendererMatch& m : matches)
            each.push_back(m.preset + " (" + m.evidence + ")");
        throw LayerError("the image looks like more than one renderer's: " +
                         OIIO::Strutil::join(each, " and ") + "; name one with from=");
    }
    return matches.empty() ? RendererMatch{} : matches.front();
}

std::string resolve_renderer_preset(const OIIO::ImageSpec& spec, const std::string& preset)
{
    if (preset == "auto")
        return detect_renderer(spec).preset;
    if (preset != "statmc")
        named_preset(preset);
    return preset;
}

ImportedImage statistics_from_preset(const OIIO::ImageBuf& src, const std::string& preset)
{
    const Preset& p = named_preset(preset);
    if (!p.variance_of)
        throw LayerError(std::string("a ") + p.renderer + " file (from=" + p.name +
                         ") holds no statistics to denoise: " + p.no_statistics);
    return import_image(src, p, true);
}

ImportedImage render_from_preset(const OIIO::ImageBuf& src, const std::string& preset)
{
    return import_image(src, named_preset(preset), false);
}

const OIIO::ImageBuf& contract_beauty(const OIIO::ImageBuf& src, ImportedImage& scratch)
{
    const OIIO::ImageSpec& spec = src.spec();
    if (spec.channelindex("R") >= 0 && spec.channelindex("G") >= 0 && spec.channelindex("B") >= 0)
        return src;
    const std::string preset = resolve_renderer_preset(spec, "auto");
    if (preset.empty() || preset == "statmc")
        return src;
    scratch = render_from_preset(src, preset);
    return scratch.image;
}

}  // namespace statmc::layers
