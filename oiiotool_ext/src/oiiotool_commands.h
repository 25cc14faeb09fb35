// The commands oiiotool 2.4 knows, so that one statmc does not implement is refused by
// name instead of being read as a typo or, worse, an input file.
#pragma once

#include <string_view>

namespace statmc::tool {

/// Whether `name` ("--flip", "-otex") is an oiiotool 2.4.7 command.
bool is_oiiotool_command(std::string_view name);

}  // namespace statmc::tool
