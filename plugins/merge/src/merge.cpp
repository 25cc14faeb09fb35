#include "statmc/merge/merge.h"
#include "statmc/merge/merge_provenance.h"

#include <algorithm>
#include <array>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "statmc/core/statistics_image.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/frame_match.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/sample_provenance.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/layers/statistics_validation.h"

namespace statmc {

namespace {

using Parts = std::vector<const OIIO::ImageBuf*>;
namespace attr = layers::attr;

std::string label(const Parts& parts, std::size_t k)
{
    return layers::input_label("part", k, parts[k]);
}

void check_part(const Parts& parts, std::size_t k)
{
    const OIIO::ImageBuf* p = parts[k];
    if (!p || !p->initialized())
        throw std::invalid_argument("part " + std::to_string(k) + " is uninitialized");
    if (p->spec().get_int_attribute(attr::kDenoised, 0) == 1)
        throw std::invalid_argument(label(parts, k) +
                                    " is denoised (statmc:denoised=1); merge takes the "
                                    "statistics as rendered");
}

// The layer contract's version must agree too: the frame and channels are not enough.
void check_format_version(const Parts& parts, std::size_t k)
{
    const int va = parts[k]->spec().get_int_attribute(attr::kFormatVersion, 0);
    const int vb = parts[0]->spec().get_int_attribute(attr::kFormatVersion, 0);
    if (va != vb)
        throw std::invalid_argument(
            OIIO::Strutil::fmt::format("{} and {} differ in statmc:formatVersion: {} vs {}",
                                       label(parts, k), label(parts, 0), va, vb));
}

template <int C>
StatisticsPlanes merge_views(const std::vector<StatisticsView>& views, int nthreads)
{
    return StatisticsImage<C>::merged(views, layers::thread_count(nthreads)).planes();
}

// The channels of one guide layer in every part (an empty list when a part lacks it).
using GuideChannels = std::vector<std::vector<int>>;

GuideChannels guide_channels(const std::vector<const OIIO::ImageBuf*>& floats,
                             const std::function<std::vector<int>(const OIIO::ImageSpec&)>& find)
{
    GuideChannels channels;
    for (const OIIO::ImageBuf* part : floats) {
        channels.push_back(find(part->spec()));
        if (channels.back().empty())
            return {};
    }
    return channels;
}

// Sample-weighted mean of a guide over the parts, in dense channel-major planes.
std::vector<float> merged_guide(const std::vector<const OIIO::ImageBuf*>& floats,
                                const std::vector<StatisticsView>& views,
                                const GuideChannels& channels)
{
    if (channels.empty())
        return {};
    const int w = views[0].width, h = views[0].height, nc = int(channels[0].size());
    std::vector<float> sum(std::size_t(nc) * w * h, 0.f), weight(std::size_t(w) * h, 0.f);
    for (std::size_t k = 0; k < floats.size(); ++k)
        for (int c = 0; c < nc; ++c) {
            const ConstPlane plane = layers::channel_plane(*floats[k], channels[k][c]);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const float n = views[k].count(x, y);
                    if (c == 0)
                        weight[std::size_t(y) * w + x] += n;
                    sum[(std::size_t(c) * h + y) * w + x] += n * plane(x, y);
                }
        }
    for (std::size_t i = 0; i < sum.size(); ++i) {
        const float n = weight[i % weight.size()];
        sum[i] = n > 0 ? sum[i] / n : 0.f;
    }
    return sum;
}

// A guide's variance (albedoVariance.Y: per-sample, summed over channels) over the parts,
// exactly as one render of all their samples would have it: the pooled within-part sums of
// squares plus each part's spread about the merged mean `merged`. Empty unless every part
// has the guide and its variance.
std::vector<float> merged_guide_variance(const std::vector<const OIIO::ImageBuf*>& floats,
                                         const std::vector<StatisticsView>& views,
                                         const GuideChannels& guide, const char* guide_layer,
                                         const std::vector<float>& merged)
{
    if (guide.empty())
        return {};
    std::vector<ConstPlane> variance;
    for (const OIIO::ImageBuf* part : floats) {
        variance.push_back(layers::guide_variance_plane(*part, guide_layer));
        if (!variance.back())
            return {};
    }
    const int w = views[0].width, h = views[0].height, nc = int(guide[0].size());
    const std::size_t pixels = std::size_t(w) * h;
    std::vector<double> squares(pixels, 0.0), count(pixels, 0.0);
    for (std::size_t k = 0; k < floats.size(); ++k) {
        const ConstPlane& v = variance[k];
        std::vector<ConstPlane> g;
        for (int c = 0; c < nc; ++c)
            g.push_back(layers::channel_plane(*floats[k], guide[k][c]));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const double n = views[k].count(x, y);
                if (!(n > 0))
                    continue;
                double spread = 0;
                for (int c = 0; c < nc; ++c) {
                    const double d = double(g[c](x, y)) - merged[c * pixels + i];
                    spread += d * d;
                }
                squares[i] += (n - 1) * double(v(x, y)) + n * spread;
                count[i] += n;
            }
    }
    std::vector<float> out(pixels);
    for (std::size_t i = 0; i < pixels; ++i)
        out[i] = count[i] > 1 ? float(squares[i] / (count[i] - 1)) : 0.f;
    return out;
}

std::array<ConstPlane, 3> dense_planes(const std::vector<float>& planes, int w, int h)
{
    if (planes.empty())
        return {};
    const std::size_t n = std::size_t(w) * h;
    return {dense_plane(planes.data(), w), dense_plane(planes.data() + n, w),
            dense_plane(planes.data() + 2 * n, w)};
}

std::optional<int> summed_spp(const Parts& parts)
{
    int total = 0;
    for (const OIIO::ImageBuf* p : parts) {
        const OIIO::ParamValue* spp = p->spec().find_attribute(attr::kSpp, OIIO::TypeInt);
        if (!spp)
            return std::nullopt;
        total += spp->get_int();
    }
    return total;
}

OIIO::ImageBuf merge_parts(const Parts& parts, const MergeOptions& options, int nthreads)
{
    // One part is a merge too when it is a whole task set (a frame of one task) or, with
    // allow_partial, what is left of one.
    const bool whole_task = parts.size() == 1 && parts[0] &&
                            parts[0]->spec().get_int_attribute(layers::attr::kTaskCount, 0) == 1;
    if (parts.empty() || (parts.size() == 1 && !options.allow_partial && !whole_task))
        throw std::invalid_argument("merge needs at least 2 images, got " +
                                    std::to_string(parts.size()));
    for (std::size_t k = 0; k < parts.size(); ++k)
        check_part(parts, k);
    layers::require_matching_inputs(parts, "part");
    for (std::size_t k = 1; k < parts.size(); ++k)
        check_format_version(parts, k);
    const MergedProvenance provenance = check_merge_provenance(parts, options.allow_partial);
    std::vector<OIIO::ImageBuf> scratch(parts.size());
    std::vector<const OIIO::ImageBuf*> floats;
    std::vector<StatisticsView> views;
    const OIIO::ImageSpec& first = parts[0]->spec();
    const std::vector<float> zeros(std::size_t(first.width) * first.height, 0.f);
    // A statistic is merged when every part has it; otherwise it is left out.
    bool box_cox = true, moments = true, box_cox_moment4 = true;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        floats.push_back(&layers::local_float_pixels(*parts[k], scratch[k]));
        try {
            const layers::StatisticsChannels ch = layers::find_statistics(floats[k]->spec());
            layers::require_statistic(floats[k]->spec(), ch, layers::Statistic::Variance);
            // Merging combines every statistic, so every one must be sound.
            if (const auto problems = layers::validate_statistics(*floats[k], ch);
                !problems.empty())
                throw layers::LayerError(layers::join_messages(problems));
            box_cox = box_cox && ch.has_box_cox();
            moments = moments && ch.has(layers::Statistic::Moment4);
            box_cox_moment4 =
                box_cox_moment4 && ch.has_box_cox() && ch.has(layers::Statistic::BoxCoxMoment4);
            views.push_back(with_stand_in_box_cox(layers::statistics_view(*floats[k], ch),
                                                  dense_plane(zeros.data(), first.width)));
        } catch (const layers::LayerError& e) {
            throw std::invalid_argument(label(parts, k) + ": " + e.what());
        }
    }
    StatisticsPlanes merged =
        views[0].channels == 1 ? merge_views<1>(views, nthreads) : merge_views<3>(views, nthreads);
    if (!box_cox)
        merged.bc_mean.clear(), merged.bc_variance.clear(), merged.bc_moment3.clear();
    if (!moments)
        merged.moment3.clear(), merged.moment4.clear();
    if (!box_cox_moment4)
        merged.bc_moment4.clear();

    const int w = first.width, h = first.height;
    const GuideChannels albedo_channels = guide_channels(floats, [](const OIIO::ImageSpec& spec) {
        return layers::find_guide_layer(spec, layers::kAlbedoLayer, true);
    });
    const GuideChannels normal_channels = guide_channels(floats, [](const OIIO::ImageSpec& spec) {
        return layers::find_guide_layer(spec, layers::kNormalLayer, false);
    });
    const std::vector<float> albedo = merged_guide(floats, views, albedo_channels);
    const std::vector<float> normal = merged_guide(floats, views, normal_channels);
    const std::vector<float> albedo_variance =
        merged_guide_variance(floats, views, albedo_channels, layers::kAlbedoLayer, albedo);
    const std::vector<float> normal_variance =
        merged_guide_variance(floats, views, normal_channels, layers::kNormalLayer, normal);
    const std::vector<float> depth =
        merged_guide(floats, views, guide_channels(floats, [](const OIIO::ImageSpec& spec) {
                         const int i =
                             spec.channelindex(layers::channel_name(layers::kDepthLayer, "Z"));
                         return i < 0 ? std::vector<int>{} : std::vector<int>{i};
                     }));
    layers::GuidePlanes guides;
    guides.albedo = dense_planes(albedo, w, h);
    guides.normal = dense_planes(normal, w, h);
    if (!depth.empty())
        guides.depth = dense_plane(depth.data(), w);
    if (!albedo_variance.empty())
        guides.albedo_variance = dense_plane(albedo_variance.data(), w);
    if (!normal_variance.empty())
        guides.normal_variance = dense_plane(normal_variance.data(), w);
    layers::StatisticsMetadata metadata;
    metadata.spp = summed_spp(parts);
    OIIO::ImageBuf out = layers::make_statistics_image(merged, metadata, guides);
    layers::write_sample_provenance(out.specmod(), provenance.merged);
    const int missing = int(provenance.missing_tasks.size());
    if (missing > 0)
        out.specmod().attribute(layers::attr::kTasksMissing, missing);
    out.set_origin(first.x, first.y);
    out.set_full(first.full_x, first.full_x + first.full_width, first.full_y,
                 first.full_y + first.full_height, first.full_z, first.full_z + first.full_depth);
    return out;
}

}  // namespace

bool merge(OIIO::ImageBuf& dst, const Parts& parts, const MergeOptions& options, int nthreads)
{
    return layers::errors_on(dst, "merge", [&] {
        dst = merge_parts(parts, options, nthreads);
        return true;
    });
}

OIIO::ImageBuf merge(const Parts& parts, const MergeOptions& options, int nthreads)
{
    return layers::returned_image(
        "merge", [&](OIIO::ImageBuf& dst) { return merge(dst, parts, options, nthreads); });
}

}  // namespace statmc
