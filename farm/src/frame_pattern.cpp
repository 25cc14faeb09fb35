#include "statmc/farm/frame_pattern.h"

#include <cctype>
#include <charconv>
#include <cstdio>
#include <stdexcept>

namespace statmc::farm {

namespace {

// Scans `pattern` and calls `on_frame(width, zero_pad)` at each %[0][width]d; literal text
// goes to `out`. Any other conversion throws.
template <class OnFrame>
int scan(const std::string& pattern, std::string* out, OnFrame&& on_frame)
{
    int conversions = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            if (out)
                *out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            if (out)
                *out += '%';
            ++i;
            continue;
        }
        std::size_t j = i + 1;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])))
            ++j;
        if (j >= pattern.size() || pattern[j] != 'd' || j - i > 4)
            throw std::runtime_error("'" + pattern +
                                     "': only one frame number (%d, %4d or %04d) may be "
                                     "substituted; write a percent sign as %%");
        const int width = j > i + 1 ? std::stoi(pattern.substr(i + 1, j - i - 1)) : 0;
        on_frame(width, zero);
        ++conversions;
        i = j;
    }
    return conversions;
}

}  // namespace

bool has_frame_number(const std::string& pattern)
{
    return scan(pattern, nullptr, [](int, bool) {}) > 0;
}

std::string expand_frame(const std::string& pattern, int frame)
{
    std::string out;
    const int n = scan(pattern, &out, [&](int width, bool zero) {
        char text[32];
        std::snprintf(text, sizeof text, zero ? "%0*d" : "%*d", width, frame);
        out += text;
    });
    if (n > 1)
        throw std::runtime_error("'" + pattern + "': more than one frame number");
    return out;
}

std::vector<int> parse_frames(const std::string& text)
{
    auto fail = [&]() -> std::runtime_error {
        return std::runtime_error("--frames: expected A-B or A (frame numbers, A <= B), got '" +
                                  text + "'");
    };
    const char* end = text.data() + text.size();
    int first = 0, last = 0;
    const auto a = std::from_chars(text.data(), end, first);
    if (a.ec != std::errc() || a.ptr == text.data())
        throw fail();
    last = first;
    if (a.ptr != end) {
        if (*a.ptr != '-')
            throw fail();
        const auto b = std::from_chars(a.ptr + 1, end, last);
        if (b.ec != std::errc() || b.ptr != end || b.ptr == a.ptr + 1)
            throw fail();
    }
    if (last < first || last - first >= 100000)
        throw fail();
    std::vector<int> frames;
    for (int f = first; f <= last; ++f)
        frames.push_back(f);
    return frames;
}

}  // namespace statmc::farm
