// Range checks for statmc-render's numeric options, said in words: CLI11's PositiveNumber
// and NonNegativeNumber print the largest double as their upper bound. Header-only: only
// programs that link CLI11 include it.
#pragma once

#include <charconv>
#include <cmath>
#include <string>

#include <CLI/CLI.hpp>

namespace statmc::render {

/// A whole number ≥ `minimum`.
inline CLI::Validator integer_at_least(int minimum)
{
    return CLI::Validator(
        [minimum](std::string& text) -> std::string {
            int value = 0;
            const char* end = text.data() + text.size();
            const auto r = std::from_chars(text.data(), end, value);
            if (r.ec != std::errc() || r.ptr != end || value < minimum)
                return "must be an integer >= " + std::to_string(minimum) + ", got '" + text + "'";
            return {};
        },
        "INT>=" + std::to_string(minimum));
}

/// A finite number ≥ `minimum`.
inline CLI::Validator number_at_least(double minimum)
{
    const std::string bound = CLI::detail::to_string(minimum);
    return CLI::Validator(
        [minimum, bound](std::string& text) -> std::string {
            double value = 0;
            if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value < minimum)
                return "must be a number >= " + bound + ", got '" + text + "'";
            return {};
        },
        "NUMBER>=" + bound);
}

}  // namespace statmc::render
