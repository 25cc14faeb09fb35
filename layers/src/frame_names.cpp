#include "statmc/layers/frame_names.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>

namespace statmc::layers {

namespace {

// OIIO walks every number between a range's ends, whatever its step, and does not check
// for overflow: the walk is bounded here before OIIO sees the list (fuzzing found
// "--frames 1-999999999" taking gigabytes).
// A run of 1–9 digits at `at` (frame numbers stay far from int's limits); advances `at`.
std::optional<long long> digits(const std::string& text, std::size_t& at)
{
    const std::size_t start = at;
    while (at < text.size() && std::isdigit(static_cast<unsigned char>(text[at])) &&
           at - start < 10)
        ++at;
    if (at == start || at - start > 9)
        return std::nullopt;
    return std::stoll(text.substr(start, at - start));
}

// The numbers OIIO would walk for one item: N, N-M, N-MxS or N-MyS (S may be negative);
// nullopt when the item is not of that form.
std::optional<long long> item_walk(const std::string& item)
{
    std::size_t at = 0;
    const auto first = digits(item, at);
    if (!first)
        return std::nullopt;
    if (at == item.size())
        return 1;
    if (item[at++] != '-')
        return std::nullopt;
    const auto last = digits(item, at);
    if (!last)
        return std::nullopt;
    if (at < item.size()) {
        if (item[at] != 'x' && item[at] != 'y')
            return std::nullopt;
        if (++at < item.size() && item[at] == '-')
            ++at;
        if (!digits(item, at) || at != item.size())
            return std::nullopt;
    }
    return std::llabs(*last - *first) + 1;
}

bool well_formed_and_bounded(const std::string& list)
{
    long long walk = 0;
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        const auto item = item_walk(list.substr(start, comma - start));
        if (!item || (walk += *item) > kMaxFrames)
            return false;
        start = comma + 1;
    }
    return true;
}

}  // namespace

std::string frame_pattern(const std::string& text, std::string* range)
{
    std::string pattern, spec;
    if (!OIIO::Filesystem::parse_pattern(text.c_str(), 0, pattern, spec))
        return "";
    // printf would pad a frame number to any width asked (%0999999999d is a gigabyte).
    if (const std::size_t percent = pattern.find('%'); percent != std::string::npos) {
        std::size_t start = percent + 1;
        while (start < pattern.size() && pattern[start] == '0')
            ++start;
        std::size_t end = start;
        while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end])))
            ++end;
        if (end - start > 2 ||
            (end > start && std::stoi(pattern.substr(start, end - start)) > kMaxFramePadding))
            throw std::invalid_argument(text + ": a frame pattern pads to at most " +
                                        std::to_string(kMaxFramePadding) + " digits");
    }
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
    if (!well_formed_and_bounded(list) || !OIIO::Filesystem::enumerate_sequence(list, frames) ||
        frames.empty())
        return std::nullopt;
    return frames;
}

}  // namespace statmc::layers
