// Splitting argument text into its items: "R,G,B" → {"R", "G", "B"}, keeping empty items
// ("," → {"", ""}) since oiiotool's lists give them a meaning (--chnames ,,,A); and
// joining them back for messages.
#pragma once

#include <string>
#include <vector>

namespace statmc::tool {

std::vector<std::string> split_text(const std::string& text, char separator = ',');

/// The items with `separator` between them: {"R", "G"} → "R, G".
std::string join_text(const std::vector<std::string>& items, const std::string& separator = ", ");

}  // namespace statmc::tool
