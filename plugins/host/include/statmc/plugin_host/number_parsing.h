// Strict number parsing for command arguments: the whole text must be the number, so
// "abc", "3x" and "" are errors rather than 0 or 3.
#pragma once

#include <optional>
#include <string_view>

namespace statmc::host {

/// The integer that is the whole of `text`, or nothing (not a number, out of range).
std::optional<int> try_parse_int(std::string_view text);

/// The finite number that is the whole of `text`, or nothing ("nan" and "inf" included).
std::optional<double> try_parse_float(std::string_view text);

/// Throws HostError "<what>: expected an integer, got 'abc'".
int parse_int(std::string_view text, std::string_view what);

/// A finite decimal or scientific number. Throws HostError
/// "<what>: expected a number, got 'abc'".
double parse_float(std::string_view text, std::string_view what);

}  // namespace statmc::host
