// oiiotool's argument lists: "R,G,B" → {"R", "G", "B"}. Empty items are kept ("," →
// {"", ""}) since oiiotool's lists give them a meaning (--chnames ,,,A).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <OpenImageIO/strutil.h>

namespace statmc::host {

/// OIIO::Strutil::splits, except that "" is one empty item rather than none, so that an
/// empty list is refused like an empty entry instead of meaning "nothing".
inline std::vector<std::string> split_text(std::string_view text, char separator = ',')
{
    if (text.empty())
        return {std::string()};
    return OIIO::Strutil::splits(text, std::string_view(&separator, 1));
}

}  // namespace statmc::host
