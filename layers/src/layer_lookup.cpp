#include "statmc/layers/layer_lookup.h"

#include <algorithm>
#include <cctype>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_names.h"

namespace statmc::layers {

namespace {

std::string layer_of(const std::string& channel)
{
    const auto dot = channel.rfind('.');
    return dot == std::string::npos ? std::string() : channel.substr(0, dot);
}

bool equal_ignoring_case(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

// A layer as a message names it: the unprefixed one by its channels ("R,G,B,A").
std::string display_name(const OIIO::ImageSpec& spec, std::string_view layer)
{
    if (!layer.empty())
        return std::string(layer);
    std::string channels;
    for (const std::string& channel : spec.channelnames)
        if (layer_of(channel).empty())
            channels += (channels.empty() ? "" : ",") + channel;
    return channels;
}

}  // namespace

std::vector<int> channel_indices(const OIIO::ImageSpec& spec, std::string_view layer,
                                 const std::vector<std::string>& suffixes)
{
    std::vector<int> indices;
    indices.reserve(suffixes.size());
    for (const std::string& suffix : suffixes)
        indices.push_back(spec.channelindex(channel_name(layer, suffix)));
    return indices;
}

bool all_present(const std::vector<int>& indices)
{
    return std::all_of(indices.begin(), indices.end(), [](int i) { return i >= 0; });
}

bool none_present(const std::vector<int>& indices)
{
    return std::all_of(indices.begin(), indices.end(), [](int i) { return i < 0; });
}

std::string describe_layer(std::string_view layer, const std::vector<std::string>& suffixes)
{
    std::string text = layer.empty() ? std::string("beauty") : std::string(layer);
    text += " (channels ";
    for (std::size_t i = 0; i < suffixes.size(); ++i) {
        if (i)
            text += ", ";
        text += channel_name(layer, suffixes[i]);
    }
    return text + ")";
}

std::vector<std::string> layers_in(const OIIO::ImageSpec& spec)
{
    std::vector<std::string> layers;
    for (const std::string& channel : spec.channelnames) {
        std::string layer = layer_of(channel);
        if (std::find(layers.begin(), layers.end(), layer) == layers.end())
            layers.push_back(std::move(layer));
    }
    return layers;
}

std::string missing_layer_message(const OIIO::ImageSpec& spec, std::string_view layer,
                                  const std::vector<std::string>& suffixes, std::string_view kind,
                                  std::string_view why)
{
    std::string message = "missing " + std::string(kind) + " " + describe_layer(layer, suffixes);
    if (!why.empty())
        message += "; " + std::string(why);
    const std::vector<std::string> present = layers_in(spec);
    message += "; the image has ";
    if (present.empty())
        message += "no channels";
    for (std::size_t i = 0; i < present.size(); ++i)
        message += (i ? ", " : "layers ") + display_name(spec, present[i]);
    // A layer differing only in case is the commonest naming slip ("Variance").
    for (const std::string& other : present)
        if (other != layer && equal_ignoring_case(other, layer))
            message += "; did you mean " + other + "?";
    return message;
}

std::vector<int> optional_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                                const std::vector<std::string>& suffixes)
{
    std::vector<int> indices = channel_indices(spec, layer, suffixes);
    if (none_present(indices))
        return {};
    if (!all_present(indices)) {
        std::string missing;
        for (std::size_t i = 0; i < indices.size(); ++i)
            if (indices[i] < 0)
                missing += (missing.empty() ? "" : ", ") + channel_name(layer, suffixes[i]);
        throw LayerError("incomplete layer " + describe_layer(layer, suffixes) + ": missing " +
                         missing);
    }
    return indices;
}

std::vector<int> require_layer(const OIIO::ImageSpec& spec, std::string_view layer,
                               const std::vector<std::string>& suffixes)
{
    std::vector<int> indices = optional_layer(spec, layer, suffixes);
    if (indices.empty())
        throw LayerError(missing_layer_message(spec, layer, suffixes));
    return indices;
}

}  // namespace statmc::layers
