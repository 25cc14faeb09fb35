#include "statmc/layers/layer_names.h"

#include "statmc/layers/layer_error.h"

namespace statmc::layers {

const std::vector<Statistic>& all_statistics()
{
    static const std::vector<Statistic> all = {Statistic::Mean,          Statistic::Variance,
                                               Statistic::BoxCoxMean,    Statistic::BoxCoxVariance,
                                               Statistic::BoxCoxMoment3, Statistic::Moment3,
                                               Statistic::Moment4,       Statistic::BoxCoxMoment4};
    return all;
}

const char* statistic_name(Statistic stat)
{
    switch (stat) {
    case Statistic::Mean:
        return "mean";
    case Statistic::Variance:
        return "variance";
    case Statistic::BoxCoxMean:
        return "boxcoxMean";
    case Statistic::BoxCoxVariance:
        return "boxcoxVariance";
    case Statistic::BoxCoxMoment3:
        return "boxcoxM3";
    case Statistic::Moment3:
        return "M3";
    case Statistic::Moment4:
        return "M4";
    case Statistic::BoxCoxMoment4:
        return "boxcoxM4";
    }
    return "?";
}

std::string statistic_layer(std::string_view aov, Statistic stat)
{
    // The mean is the AOV's own layer, so that tools unaware of statmc see the image.
    if (stat == Statistic::Mean)
        return std::string(aov);
    return channel_name(aov, statistic_name(stat));
}

bool is_statistics_channel(std::string_view channel, std::string_view aov)
{
    if (channel == kSampleCountChannel)
        return true;
    const std::size_t dot = channel.rfind('.');
    if (dot == std::string_view::npos)
        return false;
    const std::string_view layer = channel.substr(0, dot);
    for (Statistic stat : all_statistics())
        if (stat != Statistic::Mean && layer == statistic_layer(aov, stat))
            return true;
    return false;
}

std::string guide_variance_layer(std::string_view guide_layer)
{
    return std::string(guide_layer) + "Variance";
}

bool is_any_statistics_channel(std::string_view channel)
{
    const std::size_t dot = channel.rfind('.');
    if (dot == std::string_view::npos)
        return false;
    const std::string_view layer = channel.substr(0, dot);
    for (const char* guide : {kAlbedoLayer, kNormalLayer})
        if (channel == channel_name(guide_variance_layer(guide), "Y"))
            return true;
    const std::size_t aov_end = layer.rfind('.');
    return is_statistics_channel(
        channel, aov_end == std::string_view::npos ? std::string_view() : layer.substr(0, aov_end));
}

std::string diagnostics_channel(std::string_view aov, std::string_view quantity)
{
    return channel_name(channel_name(aov, kDiagnosticsLayer), quantity);
}

std::string bounce_aov(BounceQuantity quantity, int bounce)
{
    if (bounce < 0)
        throw LayerError("bounce_aov: negative bounce " + std::to_string(bounce));
    const char* what = quantity == BounceQuantity::Luminance   ? "L"
                       : quantity == BounceQuantity::LightWins ? "LightWins"
                                                               : "BsdfWins";
    return "bounce" + std::to_string(bounce) + what;
}

bool is_valid_aov_name(std::string_view aov)
{
    if (aov.empty() || (aov[0] >= '0' && aov[0] <= '9'))
        return false;
    return aov.find_first_of(". \t") == std::string_view::npos;
}

std::string channel_name(std::string_view layer, std::string_view suffix)
{
    if (layer.empty())
        return std::string(suffix);
    std::string name(layer);
    name += '.';
    name += suffix;
    return name;
}

const std::vector<std::string>& colour_suffixes()
{
    static const std::vector<std::string> s = {"R", "G", "B"};
    return s;
}

const std::vector<std::string>& scalar_suffixes()
{
    static const std::vector<std::string> s = {"Y"};
    return s;
}

const std::vector<std::string>& vector_suffixes()
{
    static const std::vector<std::string> s = {"X", "Y", "Z"};
    return s;
}

const std::vector<std::string>& suffixes_for_channels(int channels)
{
    if (channels == 3)
        return colour_suffixes();
    if (channels == 1)
        return scalar_suffixes();
    throw LayerError("the layer contract stores 1 (Y) or 3 (R, G, B) channels per AOV, got " +
                     std::to_string(channels));
}

}  // namespace statmc::layers
