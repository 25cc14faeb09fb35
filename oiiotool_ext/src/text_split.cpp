#include "statmc/tool/text_split.h"

namespace statmc::tool {

std::vector<std::string> split_text(const std::string& text, char separator)
{
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t at = text.find(separator, start);
        parts.push_back(text.substr(start, at - start));
        if (at == std::string::npos)
            return parts;
        start = at + 1;
    }
}

}  // namespace statmc::tool
