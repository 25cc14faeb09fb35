#include "statmc/layers/statistics_layers.h"

#include <functional>
#include <utility>

#include "statmc/layers/float_pixels.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"

namespace statmc::layers {

namespace {

const std::vector<Statistic>& box_cox_statistics()
{
    static const std::vector<Statistic> s = {Statistic::BoxCoxMean, Statistic::BoxCoxVariance,
                                             Statistic::BoxCoxMoment3};
    return s;
}

void check_format_version(const OIIO::ImageSpec& spec)
{
    const OIIO::ParamValue* p = spec.find_attribute(attr::kFormatVersion);
    if (!p)
        return;  // other renderers' variance AOVs carry no statmc: attributes
    const int version = p->get_int(-1);
    if (version < 1 || version > kFormatVersion)
        throw LayerError(std::string(attr::kFormatVersion) + " is " + p->get_string() +
                         "; this build reads versions 1 to " + std::to_string(kFormatVersion));
}

void check_box_cox_lambda(const OIIO::ImageSpec& spec)
{
    const OIIO::ParamValue* p = spec.find_attribute(attr::kBoxCoxLambda);
    if (p && p->get_float(-1.f) != kBoxCoxLambda)
        throw LayerError(std::string(attr::kBoxCoxLambda) + " is " + p->get_string() +
                         "; the Box-Cox statistics must use lambda 0.5");
}

bool read_variance_of_mean(const OIIO::ImageSpec& spec)
{
    const OIIO::ParamValue* p = spec.find_attribute(attr::kVariance);
    if (!p)
        return false;
    const std::string kind = p->get_string();
    if (kind == kVarianceOfSample)
        return false;
    if (kind == kVarianceOfMean)
        return true;
    throw LayerError(std::string(attr::kVariance) + " must be \"" + kVarianceOfSample + "\" or \"" +
                     kVarianceOfMean + "\", got \"" + kind + "\"");
}

// The mean layer decides whether the AOV is colour (R,G,B) or scalar (Y).
std::pair<std::vector<std::string>, std::vector<int>> find_mean(const OIIO::ImageSpec& spec,
                                                                std::string_view aov)
{
    std::vector<int> colour = channel_indices(spec, aov, colour_suffixes());
    if (all_present(colour))
        return {colour_suffixes(), colour};
    std::vector<int> scalar = channel_indices(spec, aov, scalar_suffixes());
    if (all_present(scalar) && none_present(colour))
        return {scalar_suffixes(), scalar};
    return {colour_suffixes(), require_layer(spec, aov, colour_suffixes())};
}

void find_box_cox(const OIIO::ImageSpec& spec, StatisticsChannels& ch)
{
    int present = 0;
    for (Statistic stat : box_cox_statistics()) {
        ch.indices(stat) = optional_layer(spec, statistic_layer(ch.aov, stat), ch.suffixes);
        present += ch.has(stat);
    }
    if (present == 0 || present == 3)
        return;
    // Half a Box-Cox set would silently fall back to the untransformed test.
    for (Statistic stat : box_cox_statistics())
        if (!ch.has(stat))
            throw LayerError(
                "incomplete Box-Cox statistics: " +
                missing_layer_message(spec, statistic_layer(ch.aov, stat), ch.suffixes));
}

// The higher moments (format version 2): M3 and M4 come together, since merging either
// needs the other. They extend the variance, and boxcoxM4 the Box-Cox set: without those
// they are not read (StatisticsView::has_moments), and the missing layer is reported by
// whoever needs it.
void find_higher_moments(const OIIO::ImageSpec& spec, StatisticsChannels& ch)
{
    for (Statistic stat : {Statistic::Moment3, Statistic::Moment4, Statistic::BoxCoxMoment4})
        ch.indices(stat) = optional_layer(spec, statistic_layer(ch.aov, stat), ch.suffixes);
    if (ch.has(Statistic::Moment3) != ch.has(Statistic::Moment4)) {
        const Statistic absent =
            ch.has(Statistic::Moment3) ? Statistic::Moment4 : Statistic::Moment3;
        throw LayerError("incomplete higher moments: " +
                         missing_layer_message(spec, statistic_layer(ch.aov, absent), ch.suffixes));
    }
}

ConstPlane plane_or_null(const OIIO::ImageBuf& buf, const std::vector<int>& indices, int c)
{
    return indices.empty() ? ConstPlane{} : channel_plane(buf, indices[c]);
}

void copy_plane(const ConstPlane& from, const Plane& to, int width, int height)
{
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            to(x, y) = from(x, y);
}

using Channels = std::vector<std::pair<std::string, ConstPlane>>;

// The mean (and, after `after_mean`, the other statistics `stats` has) of one AOV.
void layout_statistics(Channels& out, const StatisticsView& stats, const std::string& aov,
                       const std::function<void()>& after_mean)
{
    const std::vector<std::string>& suffixes = suffixes_for_channels(stats.channels);
    auto add = [&](Statistic stat, const std::array<ConstPlane, 4>& planes) {
        for (int c = 0; c < stats.channels; ++c)
            out.emplace_back(channel_name(statistic_layer(aov, stat), suffixes[c]), planes[c]);
    };
    add(Statistic::Mean, stats.mean);
    if (after_mean)
        after_mean();
    if (stats.variance[0])
        add(Statistic::Variance, stats.variance);
    if (stats.has_box_cox()) {
        add(Statistic::BoxCoxMean, stats.bc_mean);
        add(Statistic::BoxCoxVariance, stats.bc_variance);
        add(Statistic::BoxCoxMoment3, stats.bc_moment3);
    }
    if (stats.has_moments()) {
        add(Statistic::Moment3, stats.moment3);
        add(Statistic::Moment4, stats.moment4);
    }
    if (stats.has_box_cox_moment4())
        add(Statistic::BoxCoxMoment4, stats.bc_moment4);
}

// An extra AOV must be nameable, distinct, of the frame and share the beauty's counts.
void check_aov(const StatisticsView& beauty, const std::string& beauty_aov,
               const AovStatistics& extra, const std::vector<AovStatistics>& all)
{
    if (!is_valid_aov_name(extra.aov))
        throw LayerError("invalid AOV name '" + extra.aov +
                         "': it needs a first character that is no digit and no dot or space");
    int same = extra.aov == beauty_aov;
    for (const AovStatistics& other : all)
        same += other.aov == extra.aov;
    if (same > 1)
        throw LayerError("AOV " + extra.aov + " is given twice");
    const StatisticsView& s = extra.stats;
    if (s.width != beauty.width || s.height != beauty.height || !s.count || !s.mean[0])
        throw LayerError("AOV " + extra.aov + " needs the beauty's resolution, a count and a mean");
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x)
            if (s.count(x, y) != beauty.count(x, y))
                throw LayerError("AOV " + extra.aov +
                                 ": sample count differs from the beauty's at pixel (" +
                                 std::to_string(x) + ", " + std::to_string(y) + ")");
}

// The channels an image of `stats` gets, in writing order, each with its source plane.
Channels layout_channels(const StatisticsView& stats, const StatisticsMetadata& metadata,
                         const GuidePlanes& guides, const std::vector<AovStatistics>& aovs)
{
    Channels out;
    layout_statistics(out, stats, metadata.aov,
                      [&] { out.emplace_back(kSampleCountChannel, stats.count); });
    for (const AovStatistics& extra : aovs) {
        check_aov(stats, metadata.aov, extra, aovs);
        layout_statistics(out, extra.stats, extra.aov, {});
    }
    auto add_guide = [&](const char* layer, const std::vector<std::string>& names,
                         const std::array<ConstPlane, 3>& planes) {
        if (planes[0] && planes[1] && planes[2])
            for (int c = 0; c < 3; ++c)
                out.emplace_back(channel_name(layer, names[c]), planes[c]);
    };
    add_guide(kAlbedoLayer, colour_suffixes(), guides.albedo);
    add_guide(kNormalLayer, vector_suffixes(), guides.normal);
    if (guides.albedo_variance)
        out.emplace_back(channel_name(guide_variance_layer(kAlbedoLayer), "Y"),
                         guides.albedo_variance);
    if (guides.normal_variance)
        out.emplace_back(channel_name(guide_variance_layer(kNormalLayer), "Y"),
                         guides.normal_variance);
    if (guides.depth)
        out.emplace_back(channel_name(kDepthLayer, "Z"), guides.depth);
    if (guides.motion[0] && guides.motion[1]) {
        out.emplace_back(channel_name(kMotionLayer, "X"), guides.motion[0]);
        out.emplace_back(channel_name(kMotionLayer, "Y"), guides.motion[1]);
    }
    return out;
}

void set_attributes(OIIO::ImageSpec& spec, const StatisticsView& stats,
                    const StatisticsMetadata& metadata)
{
    spec.attribute(attr::kFormatVersion, kFormatVersion);
    if (stats.variance[0])
        spec.attribute(attr::kVariance,
                       stats.variance_of_mean ? kVarianceOfMean : kVarianceOfSample);
    if (stats.has_box_cox())
        spec.attribute(attr::kBoxCoxLambda, kBoxCoxLambda);
    if (metadata.spp)
        spec.attribute(attr::kSpp, *metadata.spp);
    if (metadata.seed)
        spec.attribute(attr::kSeed, *metadata.seed);
    spec.attribute("compression", "zip");
}

}  // namespace

bool StatisticsChannels::has_box_cox() const
{
    return has(Statistic::BoxCoxMean) && has(Statistic::BoxCoxVariance) &&
           has(Statistic::BoxCoxMoment3);
}

const std::vector<int>& StatisticsChannels::indices(Statistic stat) const
{
    switch (stat) {
    case Statistic::Mean:
        return mean;
    case Statistic::Variance:
        return variance;
    case Statistic::BoxCoxMean:
        return bc_mean;
    case Statistic::BoxCoxVariance:
        return bc_variance;
    case Statistic::BoxCoxMoment3:
        return bc_moment3;
    case Statistic::Moment3:
        return moment3;
    case Statistic::Moment4:
        return moment4;
    case Statistic::BoxCoxMoment4:
        return bc_moment4;
    }
    return mean;
}

std::vector<int>& StatisticsChannels::indices(Statistic stat)
{
    return const_cast<std::vector<int>&>(std::as_const(*this).indices(stat));
}

std::string StatisticsChannels::channel(Statistic stat, int c) const
{
    return channel_name(statistic_layer(aov, stat), suffixes.at(c));
}

namespace {

// What a user without a sample count should do: a plain render (no statistic of the AOV at
// all) needs passes or a renderer that writes statistics; a variance AOV needs the count.
std::string missing_count_advice(const OIIO::ImageSpec& spec, const StatisticsChannels& ch)
{
    bool any_statistic = false;
    for (Statistic stat : {Statistic::Variance, Statistic::BoxCoxMean, Statistic::BoxCoxVariance})
        any_statistic =
            any_statistic ||
            !none_present(channel_indices(spec, statistic_layer(ch.aov, stat), ch.suffixes));
    if (!any_statistic)
        return "this looks like a plain render, which holds no per-pixel statistics: render K >= 2 "
               "passes with different seeds and combine them (statmc a.exr b.exr c.exr d.exr "
               "--passes --denoise -o out.exr), or have the renderer write the statistics "
               "(docs/exr-layers.md); for another renderer's statistics, name its preset "
               "(--denoise:from=renderman, pbrt-v4; docs/renderers.md)";
    return "the number of samples of each pixel; for a render with the same count everywhere, "
           "append it as a constant layer (oiiotool in.exr --pattern constant:color=SPP WxH 1 "
           "--chnames sampleCount.Y --chappend -o out.exr)";
}

}  // namespace

StatisticsChannels find_statistics(const OIIO::ImageSpec& spec, std::string_view aov)
{
    check_format_version(spec);
    check_box_cox_lambda(spec);
    StatisticsChannels ch;
    ch.aov = std::string(aov);
    std::tie(ch.suffixes, ch.mean) = find_mean(spec, aov);
    ch.count = spec.channelindex(kSampleCountChannel);
    if (ch.count < 0)
        throw LayerError(missing_layer_message(spec, kSampleCountLayer, scalar_suffixes(), "layer",
                                               missing_count_advice(spec, ch)));
    ch.variance = optional_layer(spec, statistic_layer(aov, Statistic::Variance), ch.suffixes);
    find_box_cox(spec, ch);
    find_higher_moments(spec, ch);
    ch.variance_of_mean = read_variance_of_mean(spec);
    return ch;
}

void require_statistic(const OIIO::ImageSpec& spec, const StatisticsChannels& channels,
                       Statistic stat)
{
    if (!channels.has(stat))
        throw LayerError(
            missing_layer_message(spec, statistic_layer(channels.aov, stat), channels.suffixes));
}

StatisticsView statistics_view(const OIIO::ImageBuf& buf, const StatisticsChannels& ch)
{
    StatisticsView view;
    view.width = buf.spec().width;
    view.height = buf.spec().height;
    view.channels = ch.channels();
    view.count = channel_plane(buf, ch.count);
    view.variance_of_mean = ch.variance_of_mean;
    for (int c = 0; c < view.channels; ++c) {
        view.mean[c] = channel_plane(buf, ch.mean.at(c));
        view.variance[c] = plane_or_null(buf, ch.variance, c);
        view.bc_mean[c] = plane_or_null(buf, ch.bc_mean, c);
        view.bc_variance[c] = plane_or_null(buf, ch.bc_variance, c);
        view.bc_moment3[c] = plane_or_null(buf, ch.bc_moment3, c);
        view.moment3[c] = plane_or_null(buf, ch.moment3, c);
        view.moment4[c] = plane_or_null(buf, ch.moment4, c);
        view.bc_moment4[c] = plane_or_null(buf, ch.bc_moment4, c);
    }
    return view;
}

StatisticsView read_statistics(const OIIO::ImageBuf& buf, std::string_view aov)
{
    return statistics_view(buf, find_statistics(buf.spec(), aov));
}

OIIO::ImageBuf make_statistics_image(const StatisticsView& stats,
                                     const StatisticsMetadata& metadata, const GuidePlanes& guides)
{
    return make_statistics_image(stats, metadata, guides, {});
}

OIIO::ImageBuf make_statistics_image(const StatisticsView& stats,
                                     const StatisticsMetadata& metadata, const GuidePlanes& guides,
                                     const std::vector<AovStatistics>& aovs)
{
    if (stats.width <= 0 || stats.height <= 0 || !stats.count || !stats.mean[0])
        throw LayerError("statistics need a resolution, a sample count and a mean");
    const auto channels = layout_channels(stats, metadata, guides, aovs);
    OIIO::ImageSpec spec(stats.width, stats.height, int(channels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames.clear();
    for (const auto& channel : channels)
        spec.channelnames.push_back(channel.first);
    // The constructor guessed an alpha channel from the count; there is none.
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    set_attributes(spec, stats, metadata);

    OIIO::ImageBuf image(spec, OIIO::InitializePixels::No);
    for (int i = 0; i < int(channels.size()); ++i)
        copy_plane(channels[i].second, channel_plane(image, i), stats.width, stats.height);
    return image;
}

OIIO::ImageBuf make_statistics_image(const StatisticsPlanes& stats,
                                     const StatisticsMetadata& metadata, const GuidePlanes& guides)
{
    return make_statistics_image(stats.view(), metadata, guides);
}

}  // namespace statmc::layers
