#include "statmc/plugin_host/number_parsing.h"

#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

#include "statmc/plugin_host/host_error.h"

namespace statmc::host {

namespace {

[[noreturn]] void fail(std::string_view what, std::string_view expected, std::string_view text)
{
    throw HostError(std::string(what) + ": expected " + std::string(expected) + ", got '" +
                    std::string(text) + "'");
}

// from_chars over the whole of `text`: errc() only when all of it is the number.
template <typename T>
std::errc parse_whole(std::string_view text, T& value)
{
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc())
        return ec;
    return ptr != end || text.empty() ? std::errc::invalid_argument : std::errc();
}

}  // namespace

std::optional<int> try_parse_int(std::string_view text)
{
    int value = 0;
    if (parse_whole(text, value) != std::errc())
        return std::nullopt;
    return value;
}

std::optional<double> try_parse_float(std::string_view text)
{
    double value = 0;
    // from_chars accepts "inf" and "nan"; no parameter means either.
    if (parse_whole(text, value) != std::errc() || !std::isfinite(value))
        return std::nullopt;
    return value;
}

int parse_int(std::string_view text, std::string_view what)
{
    if (const std::optional<int> value = try_parse_int(text))
        return *value;
    int ignored = 0;
    if (parse_whole(text, ignored) == std::errc::result_out_of_range)
        fail(what, "an integer in range", text);
    fail(what, "an integer", text);
}

double parse_float(std::string_view text, std::string_view what)
{
    if (const std::optional<double> value = try_parse_float(text))
        return *value;
    fail(what, "a finite number", text);
}

}  // namespace statmc::host
