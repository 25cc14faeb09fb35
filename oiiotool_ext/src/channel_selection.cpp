#include "channel_selection.h"

#include <optional>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/number_parsing.h"
#include "statmc/plugin_host/text_split.h"

namespace statmc::tool {

ChannelSelection parse_channel_selection(const std::string& list, const OIIO::ImageSpec& spec,
                                         const std::string& what)
{
    ChannelSelection sel;
    for (std::string entry : host::split_text(list)) {
        std::string name;
        const std::size_t eq = entry.find('=');
        const bool renamed = eq != std::string::npos;
        if (renamed) {
            name = entry.substr(0, eq);
            entry = entry.substr(eq + 1);
        }
        int index = spec.channelindex(entry);
        // After "=", a number is a constant (oiiotool's "A=1"); alone it is an index.
        if (index < 0 && renamed)
            if (const std::optional<double> constant = host::try_parse_float(entry)) {
                sel.order.push_back(-1);
                sel.values.push_back(float(*constant));
                sel.names.push_back(name);
                continue;
            }
        if (index < 0)
            if (const std::optional<int> number = host::try_parse_int(entry)) {
                if (*number < 0 || *number >= spec.nchannels)
                    throw host::HostError(what + ": channel index " + entry +
                                          " is out of range (the image has " +
                                          std::to_string(spec.nchannels) + " channels)");
                index = *number;
            }
        if (index < 0)
            throw host::HostError(what + ": no channel '" + entry + "' (the image has " +
                                  OIIO::Strutil::join(spec.channelnames, ", ") + ")");
        sel.order.push_back(index);
        sel.values.push_back(0.f);
        sel.names.push_back(name);
    }
    return sel;
}

OIIO::ImageBuf select_channels(const OIIO::ImageBuf& image, const std::string& list,
                               const std::string& what, int nthreads)
{
    const ChannelSelection sel = parse_channel_selection(list, image.spec(), what);
    return OIIO::ImageBufAlgo::channels(image, int(sel.order.size()), sel.order, sel.values,
                                        sel.names, false, nthreads);
}

}  // namespace statmc::tool
