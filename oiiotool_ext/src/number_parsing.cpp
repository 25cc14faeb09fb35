#include "statmc/tool/number_parsing.h"

#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

#include "statmc/tool/tool_error.h"

namespace statmc::tool {

namespace {

[[noreturn]] void fail(std::string_view what, std::string_view expected, std::string_view text)
{
    throw ToolError(std::string(what) + ": expected " + std::string(expected) + ", got '" +
                    std::string(text) + "'");
}

}  // namespace

int parse_int(std::string_view text, std::string_view what)
{
    int value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec == std::errc::result_out_of_range)
        fail(what, "an integer in range", text);
    if (ec != std::errc() || ptr != end || text.empty())
        fail(what, "an integer", text);
    return value;
}

double parse_float(std::string_view text, std::string_view what)
{
    double value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    // from_chars accepts "inf" and "nan"; no parameter means either.
    if (ec != std::errc() || ptr != end || text.empty() || !std::isfinite(value))
        fail(what, "a finite number", text);
    return value;
}

}  // namespace statmc::tool
