// One typed parameter of an operator, as a plugin declares it: name, type, default,
// allowed range or choices, and a line of help. Hosts parse and check values from it,
// and print their help tables from it, so the declaration is the only description.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace statmc {

enum class ParameterType {
    Int,
    Float,
    Bool,  ///< 1/0, true/false, yes/no, on/off
    String,
    Choice,  ///< one of `choices`
    List,    ///< comma-separated items from `choices`, or one of `keywords` alone
};

/// "int", "float", "bool", "string", "choice", "list".
const char* type_name(ParameterType type);

/// Bounds of a numeric parameter; either may be absent.
struct ParameterRange {
    std::optional<double> min, max;
    bool min_exclusive = false;
    bool max_exclusive = false;

    bool empty() const { return !min && !max; }
    bool contains(double value) const;
    /// "[0, 1000]", "(0, 1)", "> 0", ">= 2", or "" without bounds.
    std::string text() const;
    /// "" when `value` is inside, else "radius must be in [0, 1000], got -1".
    std::string violation(const std::string& name, double value) const;
};

struct ParameterSpec {
    std::string name;
    ParameterType type = ParameterType::String;
    std::string default_value;  ///< as typed on a command line; empty: absent unless given
    std::string help;
    std::vector<std::string> choices;   ///< Choice and List
    std::vector<std::string> keywords;  ///< List only: values that stand alone ("auto")
    ParameterRange range;               ///< Int and Float only
    std::string syntax;  ///< String only: how help writes its value when not a name ("file")

    /// "int", "float", "auto|boxcox|untransformed", "albedo,normal|auto|none", "name", or
    /// a string parameter's own syntax
    std::string value_syntax() const;

    /// A string parameter whose values are not names: how help writes them ("int,...").
    ParameterSpec& written_as(std::string value_syntax);

    // Range setters, chained after a builder: int_parameter(...).between(0, 1000).
    ParameterSpec& between(double lo, double hi);       ///< [lo, hi]
    ParameterSpec& open_between(double lo, double hi);  ///< (lo, hi)
    ParameterSpec& at_least(double lo);                 ///< >= lo
    ParameterSpec& above(double lo);                    ///< > lo
};

/// Shortest readable text of a number for help and messages: 0.005, 10, 1000.
std::string number_text(double value);

// Builders, in the manner of Mitsuba's Properties: name, default, help.
ParameterSpec int_parameter(std::string name, std::optional<int> default_value, std::string help);
ParameterSpec float_parameter(std::string name, std::optional<double> default_value,
                              std::string help);
ParameterSpec bool_parameter(std::string name, std::optional<bool> default_value, std::string help);
ParameterSpec string_parameter(std::string name, std::string default_value, std::string help);
ParameterSpec choice_parameter(std::string name, std::vector<std::string> choices,
                               std::string default_value, std::string help);
ParameterSpec list_parameter(std::string name, std::vector<std::string> choices,
                             std::vector<std::string> keywords, std::string default_value,
                             std::string help);

}  // namespace statmc
