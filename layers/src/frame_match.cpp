#include "statmc/layers/frame_match.h"

#include <algorithm>

#include <OpenImageIO/strutil.h>

#include "statmc/layers/layer_error.h"

namespace statmc::layers {

void require_same_frame(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b,
                        const std::string& these)
{
    if (a.width != b.width || a.height != b.height)
        throw LayerError(OIIO::Strutil::fmt::format("{} differ in resolution: {}x{} vs {}x{}",
                                                    these, a.width, a.height, b.width, b.height));
    if (a.x != b.x || a.y != b.y)
        throw LayerError(OIIO::Strutil::fmt::format(
            "{} differ in data window: origin ({}, {}) vs ({}, {})", these, a.x, a.y, b.x, b.y));
}

std::string input_label(std::string_view noun, std::size_t k, const OIIO::ImageBuf* input)
{
    std::string text = std::string(noun) + " " + std::to_string(k);
    if (input && !input->name().empty())
        text += " (" + std::string(input->name()) + ")";
    return text;
}

namespace {

// The names in `a` that `b` lacks, comma-separated, or "none".
std::string missing_from(const std::vector<std::string>& a, const std::vector<std::string>& b)
{
    std::vector<std::string> out;
    for (const std::string& n : a)
        if (std::find(b.begin(), b.end(), n) == b.end())
            out.push_back(n);
    return out.empty() ? std::string("none") : OIIO::Strutil::join(out, ", ");
}

}  // namespace

void require_matching_specs(const OIIO::ImageSpec& a, const std::string& a_label,
                            const OIIO::ImageSpec& b, const std::string& b_label)
{
    require_same_frame(a, b, a_label + " and " + b_label);
    const std::string only_a = missing_from(a.channelnames, b.channelnames);
    const std::string only_b = missing_from(b.channelnames, a.channelnames);
    if (only_a != "none" || only_b != "none")
        throw LayerError(a_label + " and " + b_label + " differ in channels: only in " + a_label +
                         ": " + only_a + "; only in " + b_label + ": " + only_b);
}

void require_matching_inputs(const std::vector<const OIIO::ImageBuf*>& inputs,
                             std::string_view noun)
{
    for (std::size_t k = 1; k < inputs.size(); ++k)
        require_matching_specs(inputs[k]->spec(), input_label(noun, k, inputs[k]),
                               inputs[0]->spec(), input_label(noun, 0, inputs[0]));
}

}  // namespace statmc::layers
