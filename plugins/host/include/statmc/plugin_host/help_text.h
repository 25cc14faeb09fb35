// Help text layout, one width for every page (--help, --help OP, --list-ops).
// OIIO::Strutil::wordwrap would be the library's tool, but OIIO 2.4's does not break
// lines (docs/ecosystem.md, pitfalls), so the wrap is written here once.
#pragma once

#include <cstddef>
#include <string>

namespace statmc::host {

inline constexpr std::size_t kHelpWidth = 100;

/// `left` padded to `column`, then `text` word-wrapped to kHelpWidth with its continuation
/// lines indented to the same column; ends with a newline.
std::string help_line(const std::string& left, std::size_t column, const std::string& text);

}  // namespace statmc::host
