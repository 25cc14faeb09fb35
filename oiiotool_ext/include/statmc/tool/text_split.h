// Splitting argument text into its items: "R,G,B" → {"R", "G", "B"}, keeping empty items
// ("," → {"", ""}) since oiiotool's lists give them a meaning (--chnames ,,,A).
#pragma once

#include <string>
#include <vector>

namespace statmc::tool {

std::vector<std::string> split_text(const std::string& text, char separator = ',');

}  // namespace statmc::tool
