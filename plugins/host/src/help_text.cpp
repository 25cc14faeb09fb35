#include "statmc/plugin_host/help_text.h"

#include <algorithm>
#include <sstream>

namespace statmc::host {

std::string help_line(const std::string& left, std::size_t column, const std::string& text)
{
    std::string out, line = left;
    line.resize(std::max(column, left.size() + 1), ' ');
    const std::string indent(column, ' ');
    std::istringstream words(text);
    std::string word;
    bool first = true;
    while (words >> word) {
        if (!first && line.size() + 1 + word.size() > kHelpWidth) {
            out += line + "\n";
            line = indent;
            first = true;
        }
        line += (first ? "" : " ") + word;
        first = false;
    }
    return out + line + "\n";
}

}  // namespace statmc::host
