#include "statmc/passes/passes.h"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/strutil.h>

#include "statmc/core/passes.h"
#include "statmc/core/sample_independence.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/frame_match.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/renderer_presets.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/layers/view_window.h"

namespace statmc {

namespace {

using Renders = std::vector<const OIIO::ImageBuf*>;

std::string label(const Renders& renders, std::size_t k)
{
    return layers::input_label("render", k, renders[k]);
}

void check_render(const Renders& renders, std::size_t k)
{
    const OIIO::ImageBuf* r = renders[k];
    if (!r || !r->initialized())
        throw std::invalid_argument(label(renders, k) + " is uninitialized");
    if (r->deep() || r->spec().depth > 1)
        throw std::invalid_argument(label(renders, k) + " is a deep or volume image");
    // Averaging statistics layers as if they were radiance would be silently wrong.
    for (const std::string& channel : r->spec().channelnames)
        if (layers::is_statistics_channel(channel))
            throw std::invalid_argument(label(renders, k) + " already holds statistics (" +
                                        channel + "); passes takes plain renders");
}

// The samples per pixel a render's header declares, where a renderer writes them: Blender
// Cycles' `cycles.<view layer>.samples`. Empty when the header says nothing.
std::optional<long> declared_samples(const OIIO::ImageSpec& spec, std::string& attribute)
{
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string name = p.name().string();
        if (!OIIO::Strutil::starts_with(name, "cycles.") ||
            !OIIO::Strutil::ends_with(name, ".samples"))
            continue;
        const std::string text = p.get_string();
        char* end = nullptr;
        const long value = std::strtol(text.c_str(), &end, 10);
        if (end != text.c_str() && *end == '\0') {
            attribute = name;
            return value;
        }
    }
    return std::nullopt;
}

// Each pass is one sample of the pixel's estimator, so passes of different sample counts
// (an 8-spp pass beside a 16384-spp reference) must not be averaged as equals.
void require_one_sample_count(const Renders& renders)
{
    std::optional<long> first;
    std::size_t first_k = 0;
    for (std::size_t k = 0; k < renders.size(); ++k) {
        std::string attribute;
        const std::optional<long> n = declared_samples(renders[k]->spec(), attribute);
        if (!n)
            continue;
        if (!first) {
            first = n;
            first_k = k;
        } else if (*n != *first) {
            throw std::invalid_argument(
                label(renders, k) + " declares " + std::to_string(*n) + " samples per pixel (" +
                attribute + ") and " + label(renders, first_k) + " " + std::to_string(*first) +
                ": passes takes renders of one sample count (each is one sample of the "
                "pixel's estimator)");
        }
    }
}

const std::vector<std::string>& beauty_suffixes(const Renders& renders)
{
    const OIIO::ImageSpec& spec = renders[0]->spec();
    if (layers::all_present(layers::channel_indices(spec, "", layers::colour_suffixes())))
        return layers::colour_suffixes();
    if (layers::all_present(layers::channel_indices(spec, "", layers::scalar_suffixes())))
        return layers::scalar_suffixes();
    throw std::invalid_argument(label(renders, 0) + ": " +
                                layers::missing_layer_message(spec, "", layers::colour_suffixes()));
}

// Planes of the named channels of `buf`, shifted so (0, 0) is the region's corner.
std::vector<ConstPlane> region_planes(const OIIO::ImageBuf& buf,
                                      const std::vector<std::string>& names,
                                      const OIIO::ROI& region)
{
    std::vector<ConstPlane> planes;
    for (const std::string& name : names)
        planes.push_back(layers::shifted(layers::channel_plane(buf, buf.spec().channelindex(name)),
                                         region.xbegin - buf.spec().x,
                                         region.ybegin - buf.spec().y));
    return planes;
}

// Channels other than the beauty, averaged over the renders.
OIIO::ImageBuf mean_of_other_channels(const std::vector<const OIIO::ImageBuf*>& floats,
                                      const std::vector<std::string>& names,
                                      const OIIO::ROI& region)
{
    OIIO::ImageSpec spec(region.width(), region.height(), int(names.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames = names;
    spec.alpha_channel = spec.channelindex("A");
    spec.z_channel = spec.channelindex("Z");
    OIIO::ImageBuf out(spec, OIIO::InitializePixels::No);
    const double k = double(floats.size());
    for (int c = 0; c < int(names.size()); ++c) {
        const Plane to = layers::channel_plane(out, c);
        std::vector<ConstPlane> from;
        for (const OIIO::ImageBuf* f : floats)
            from.push_back(region_planes(*f, {names[c]}, region)[0]);
        for (int y = 0; y < region.height(); ++y)
            for (int x = 0; x < region.width(); ++x) {
                double sum = 0;
                for (const ConstPlane& p : from)
                    sum += p(x, y);
                to(x, y) = float(sum / k);
            }
    }
    return out;
}

// The guide variance layers (albedoVariance.Y, normalVariance.Y) that K passes give: each
// render is one sample, so a guide's per-sample variance is the spread of the renders' guide
// means, Σ_c over its channels. A layer for each guide every render has.
OIIO::ImageBuf guide_variances(const std::vector<const OIIO::ImageBuf*>& floats,
                               const OIIO::ROI& region)
{
    struct Guide {
        const char* layer;
        std::vector<std::vector<ConstPlane>> planes;  // per render, 3 channels
    };
    std::vector<Guide> present;
    for (const auto& [layer, colour] :
         {std::pair{layers::kAlbedoLayer, true}, std::pair{layers::kNormalLayer, false}}) {
        Guide g{layer, {}};
        for (const OIIO::ImageBuf* f : floats) {
            const std::vector<int> indices = layers::find_guide_layer(f->spec(), layer, colour);
            if (indices.empty())
                break;
            std::vector<std::string> names;
            for (int i : indices)
                names.push_back(f->spec().channel_name(i));
            g.planes.push_back(region_planes(*f, names, region));
        }
        if (g.planes.size() == floats.size())
            present.push_back(std::move(g));
    }
    if (present.empty())
        return {};
    OIIO::ImageSpec spec(region.width(), region.height(), int(present.size()),
                         OIIO::TypeDesc::FLOAT);
    for (std::size_t g = 0; g < present.size(); ++g)
        spec.channelnames[g] =
            layers::channel_name(layers::guide_variance_layer(present[g].layer), "Y");
    OIIO::ImageBuf out(spec, OIIO::InitializePixels::No);
    const double k = double(floats.size());
    for (std::size_t g = 0; g < present.size(); ++g) {
        const Plane to = layers::channel_plane(out, int(g));
        for (int y = 0; y < region.height(); ++y)
            for (int x = 0; x < region.width(); ++x) {
                double variance = 0;
                for (int c = 0; c < 3; ++c) {
                    double sum = 0, squares = 0;
                    for (const std::vector<ConstPlane>& render : present[g].planes) {
                        const double v = render[c](x, y);
                        sum += v;
                        squares += v * v;
                    }
                    variance += std::max(0.0, (squares - sum * sum / k) / (k - 1));
                }
                to(x, y) = float(variance);
            }
    }
    return out;
}

// Renders of one seed drew the same samples: averaged, they would claim K samples where
// there is one, and their variance would be 0 (docs/method.md, "Independent samples").
void require_distinct_renders(const Renders& given,
                              const std::vector<std::vector<ConstPlane>>& beauty,
                              const OIIO::ROI& region)
{
    for (std::size_t k = 1; k < beauty.size(); ++k)
        for (std::size_t j = 0; j < k; ++j)
            if (identical_pixels(beauty[k], beauty[j], region.width(), region.height()))
                throw std::invalid_argument(
                    label(given, k) + " and " + label(given, j) +
                    " hold the same pixels: they were rendered with one seed, so they are one "
                    "sample, not two. Render each pass with its own seed (Blender: Render "
                    "Properties > Sampling > Advanced > Seed, or scene.cycles.seed = pass "
                    "number; statmc-render: --seed)");
}

void keep_metadata(OIIO::ImageBuf& result, const OIIO::ImageBuf& first, const OIIO::ROI& region)
{
    const OIIO::ParamValueList statmc_attribs = result.spec().extra_attribs;
    result.copy_metadata(first);
    OIIO::ImageSpec& spec = result.specmod();
    for (const char* name : {layers::attr::kSpp, layers::attr::kSeed, layers::attr::kDenoised,
                             layers::attr::kBoxCoxLambda})
        spec.erase_attribute(name);
    for (const OIIO::ParamValue& p : statmc_attribs)
        spec.extra_attribs.add_or_replace(p);
    result.set_origin(region.xbegin, region.ybegin);
}

// The renders under the contract's names, where a preset renames them.
Renders renamed_renders(const Renders& renders, const PassesOptions& options,
                        std::vector<layers::ImportedImage>& imported)
{
    Renders renamed = renders;
    imported.resize(renders.size());
    for (std::size_t k = 0; k < renders.size(); ++k) {
        const std::string preset =
            layers::resolve_renderer_preset(renders[k]->spec(), options.from);
        if (!preset.empty() && preset != "statmc") {
            imported[k] = layers::render_from_preset(*renders[k], preset);
            renamed[k] = &imported[k].image;
        }
    }
    return renamed;
}

bool passes_impl(OIIO::ImageBuf& dst, const Renders& given, const PassesOptions& options,
                 OIIO::ROI roi, int nthreads)
{
    if (given.size() < 2)
        throw std::invalid_argument("passes needs at least 2 renders, got " +
                                    std::to_string(given.size()));
    // Checked as given, so that messages name the files; a preset renames no statistic.
    for (std::size_t k = 0; k < given.size(); ++k)
        check_render(given, k);
    layers::require_matching_inputs(given, "render");
    require_one_sample_count(given);
    std::vector<layers::ImportedImage> imported;
    const Renders renders = renamed_renders(given, options, imported);

    const OIIO::ImageBuf& first = *renders[0];
    const OIIO::ROI region = roi.defined() ? OIIO::roi_intersection(roi, first.roi()) : first.roi();
    if (region.width() <= 0 || region.height() <= 0)
        throw std::invalid_argument("the ROI does not overlap the data window");

    std::vector<OIIO::ImageBuf> scratch(renders.size());
    std::vector<const OIIO::ImageBuf*> floats;
    for (std::size_t k = 0; k < renders.size(); ++k)
        floats.push_back(&layers::local_float_pixels(*renders[k], scratch[k]));

    const std::vector<std::string>& suffixes = beauty_suffixes(renders);
    std::vector<std::vector<ConstPlane>> beauty;
    for (const OIIO::ImageBuf* f : floats)
        beauty.push_back(region_planes(*f, suffixes, region));
    require_distinct_renders(given, beauty, region);
    const StatisticsPlanes stats = statistics_from_passes(beauty, region.width(), region.height());

    OIIO::ImageBuf result = layers::make_statistics_image(stats);
    // Every other channel (AOVs, guides) is averaged over the renders, but the guides'
    // variances, which the renders' spread replaces.
    const OIIO::ImageBuf variances = guide_variances(floats, region);
    auto replaced = [&](const std::string& name) {
        return variances.initialized() && variances.spec().channelindex(name) >= 0;
    };
    std::vector<std::string> others;
    for (const std::string& name : first.spec().channelnames)
        if (std::find(suffixes.begin(), suffixes.end(), name) == suffixes.end() && !replaced(name))
            others.push_back(name);
    auto append = [&](const OIIO::ImageBuf& more) {
        OIIO::ImageBuf appended;
        if (!OIIO::ImageBufAlgo::channel_append(appended, result, more, {}, nthreads))
            throw std::runtime_error(appended.geterror());
        result = std::move(appended);
    };
    if (!others.empty())
        append(mean_of_other_channels(floats, others, region));
    if (variances.initialized())
        append(variances);
    keep_metadata(result, first, region);
    dst = std::move(result);
    return true;
}

}  // namespace

bool passes(OIIO::ImageBuf& dst, const std::vector<const OIIO::ImageBuf*>& renders,
            const PassesOptions& options, OIIO::ROI roi, int nthreads)
{
    return layers::errors_on(dst, "passes",
                             [&] { return passes_impl(dst, renders, options, roi, nthreads); });
}

bool passes(OIIO::ImageBuf& dst, const std::vector<const OIIO::ImageBuf*>& renders, OIIO::ROI roi,
            int nthreads)
{
    return passes(dst, renders, PassesOptions{}, roi, nthreads);
}

OIIO::ImageBuf passes(const std::vector<const OIIO::ImageBuf*>& renders,
                      const PassesOptions& options, OIIO::ROI roi, int nthreads)
{
    return layers::returned_image("passes", [&](OIIO::ImageBuf& dst) {
        return passes(dst, renders, options, roi, nthreads);
    });
}

OIIO::ImageBuf passes(const std::vector<const OIIO::ImageBuf*>& renders, OIIO::ROI roi,
                      int nthreads)
{
    return passes(renders, PassesOptions{}, roi, nthreads);
}

}  // namespace statmc
