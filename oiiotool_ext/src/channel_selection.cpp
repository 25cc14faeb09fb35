#include "statmc/tool/channel_selection.h"

#include <charconv>
#include <system_error>

#include "statmc/tool/text_split.h"
#include "statmc/tool/tool_error.h"

namespace statmc::tool {

namespace {

// Sets `value` only when the whole of `text` is the number.
template <typename T>
bool parse_whole(const std::string& text, T& value)
{
    T parsed{};
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, parsed);
    if (ec != std::errc() || ptr != end || text.empty())
        return false;
    value = parsed;
    return true;
}

std::string channel_names(const OIIO::ImageSpec& spec)
{
    std::string names;
    for (const std::string& n : spec.channelnames)
        names += (names.empty() ? "" : ", ") + n;
    return names;
}

}  // namespace

ChannelSelection parse_channel_selection(const std::string& list, const OIIO::ImageSpec& spec,
                                         const std::string& what)
{
    ChannelSelection sel;
    for (std::string entry : split_text(list)) {
        std::string name;
        const std::size_t eq = entry.find('=');
        const bool renamed = eq != std::string::npos;
        if (renamed) {
            name = entry.substr(0, eq);
            entry = entry.substr(eq + 1);
        }
        int index = spec.channelindex(entry);
        float constant = 0.f;
        // After "=", a number is a constant (oiiotool's "A=1"); alone it is an index.
        if (index < 0 && renamed && parse_whole(entry, constant)) {
            sel.order.push_back(-1);
            sel.values.push_back(constant);
            sel.names.push_back(name);
            continue;
        }
        if (index < 0 && parse_whole(entry, index) &&
            (index < 0 || index >= spec.nchannels))
            throw ToolError(what + ": channel index " + entry + " is out of range (the image has " +
                            std::to_string(spec.nchannels) + " channels)");
        if (index < 0)
            throw ToolError(what + ": no channel '" + entry + "' (the image has " +
                            channel_names(spec) + ")");
        sel.order.push_back(index);
        sel.values.push_back(0.f);
        sel.names.push_back(name);
    }
    return sel;
}

}  // namespace statmc::tool
