#include "text_split.h"

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

std::string join_text(const std::vector<std::string>& items, const std::string& separator)
{
    std::string text;
    for (std::size_t k = 0; k < items.size(); ++k)
        text += (k == 0 ? "" : separator) + items[k];
    return text;
}

}  // namespace statmc::tool
