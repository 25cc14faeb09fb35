#include "statmc/plugin_sdk/parameter_spec.h"

#include <sstream>

#include <OpenImageIO/strutil.h>

namespace statmc {

std::string number_text(double value)
{
    std::ostringstream os;
    os << value;
    return os.str();
}

namespace {

ParameterSpec make(std::string name, ParameterType type, std::string default_value,
                   std::string help)
{
    ParameterSpec spec;
    spec.name = std::move(name);
    spec.type = type;
    spec.default_value = std::move(default_value);
    spec.help = std::move(help);
    return spec;
}

}  // namespace

const char* type_name(ParameterType type)
{
    switch (type) {
    case ParameterType::Int:
        return "int";
    case ParameterType::Float:
        return "float";
    case ParameterType::Bool:
        return "bool";
    case ParameterType::String:
        return "string";
    case ParameterType::Choice:
        return "choice";
    case ParameterType::List:
        return "list";
    }
    return "value";
}

bool ParameterRange::contains(double value) const
{
    if (min && (min_exclusive ? !(value > *min) : !(value >= *min)))
        return false;
    if (max && (max_exclusive ? !(value < *max) : !(value <= *max)))
        return false;
    return true;
}

std::string ParameterRange::text() const
{
    if (min && max)
        return (min_exclusive ? "(" : "[") + number_text(*min) + ", " + number_text(*max) +
               (max_exclusive ? ")" : "]");
    if (min)
        return (min_exclusive ? "> " : ">= ") + number_text(*min);
    if (max)
        return (max_exclusive ? "< " : "<= ") + number_text(*max);
    return {};
}

std::string ParameterRange::violation(const std::string& name, double value) const
{
    if (contains(value))
        return {};
    std::string rule;
    if (min && max)
        rule = "must be in " + text();
    else if (min && !min_exclusive)
        rule = "must be at least " + number_text(*min);
    else
        rule = "must be " + text();
    return name + " " + rule + ", got " + number_text(value);
}

std::string ParameterSpec::value_syntax() const
{
    using OIIO::Strutil::join;
    switch (type) {
    case ParameterType::String:
        return syntax.empty() ? "name" : syntax;
    case ParameterType::Choice:
        return join(choices, "|");
    case ParameterType::List:
        return join(choices, ",") + "|" + join(keywords, "|");
    default:
        return type_name(type);  // int, float, bool
    }
}

ParameterSpec& ParameterSpec::written_as(std::string value_syntax)
{
    syntax = std::move(value_syntax);
    return *this;
}

ParameterSpec& ParameterSpec::between(double lo, double hi)
{
    range = {lo, hi, false, false};
    return *this;
}

ParameterSpec& ParameterSpec::open_between(double lo, double hi)
{
    range = {lo, hi, true, true};
    return *this;
}

ParameterSpec& ParameterSpec::at_least(double lo)
{
    range = {lo, std::nullopt, false, false};
    return *this;
}

ParameterSpec& ParameterSpec::above(double lo)
{
    range = {lo, std::nullopt, true, false};
    return *this;
}

ParameterSpec int_parameter(std::string name, std::optional<int> default_value, std::string help)
{
    return make(std::move(name), ParameterType::Int,
                default_value ? std::to_string(*default_value) : "", std::move(help));
}

ParameterSpec float_parameter(std::string name, std::optional<double> default_value,
                              std::string help)
{
    return make(std::move(name), ParameterType::Float,
                default_value ? number_text(*default_value) : "", std::move(help));
}

ParameterSpec bool_parameter(std::string name, std::optional<bool> default_value, std::string help)
{
    const std::string text = !default_value ? "" : *default_value ? "1" : "0";
    return make(std::move(name), ParameterType::Bool, text, std::move(help));
}

ParameterSpec string_parameter(std::string name, std::string default_value, std::string help)
{
    return make(std::move(name), ParameterType::String, std::move(default_value), std::move(help));
}

ParameterSpec choice_parameter(std::string name, std::vector<std::string> choices,
                               std::string default_value, std::string help)
{
    ParameterSpec spec =
        make(std::move(name), ParameterType::Choice, std::move(default_value), std::move(help));
    spec.choices = std::move(choices);
    return spec;
}

ParameterSpec list_parameter(std::string name, std::vector<std::string> choices,
                             std::vector<std::string> keywords, std::string default_value,
                             std::string help)
{
    ParameterSpec spec =
        make(std::move(name), ParameterType::List, std::move(default_value), std::move(help));
    spec.choices = std::move(choices);
    spec.keywords = std::move(keywords);
    return spec;
}

}  // namespace statmc
