#include "statmc/layers/frame_names.h"

#include <OpenImageIO/filesystem.h>

namespace statmc::layers {

std::string frame_pattern(const std::string& text, std::string* range)
{
    std::string pattern, spec;
    if (!OIIO::Filesystem::parse_pattern(text.c_str(), 0, pattern, spec))
        return "";
    if (range)
        *range = spec;
    return pattern;
}

std::string frame_path(const std::string& pattern, int frame)
{
    std::vector<std::string> names;
    OIIO::Filesystem::enumerate_file_sequence(pattern, {frame}, names);
    return names.empty() ? "" : names.front();
}

std::optional<std::vector<int>> frame_list(const std::string& list)
{
    std::vector<int> frames;
    if (list.empty() || !OIIO::Filesystem::enumerate_sequence(list, frames) || frames.empty())
        return std::nullopt;
    return frames;
}

}  // namespace statmc::layers
