#include "statmc/plugin_host/modifiers.h"

#include <algorithm>

#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/number_parsing.h"
#include "statmc/plugin_host/text_split.h"

namespace statmc::host {

namespace {

bool contains(const std::vector<std::string>& items, const std::string& item)
{
    return std::find(items.begin(), items.end(), item) != items.end();
}

bool parse_bool(const std::string& text, const std::string& what)
{
    for (const char* yes : {"1", "true", "yes", "on"})
        if (text == yes)
            return true;
    for (const char* no : {"0", "false", "no", "off"})
        if (text == no)
            return false;
    throw HostError(what + ": expected a boolean (1/0, true/false, yes/no, on/off), got '" + text +
                    "'");
}

statmc::ParameterValue parse_text(const std::string& command, const ModifierSpec& spec,
                                  const std::string& text)
{
    const std::string what = command + ": " + spec.name;
    switch (spec.type) {
    case ModifierType::Int:
        return parse_int(text, what);
    case ModifierType::Float:
        return parse_float(text, what);
    case ModifierType::Bool:
        return parse_bool(text, what);
    case ModifierType::String:
        if (text.empty())
            throw HostError(what + ": expected a value");
        return text;
    case ModifierType::Choice:
        if (!contains(spec.choices, text))
            throw HostError(what + ": expected one of " + OIIO::Strutil::join(spec.choices, ", ") +
                            ", got '" + text + "'");
        return text;
    case ModifierType::List: {
        if (contains(spec.keywords, text))
            return std::vector<std::string>{text};
        std::vector<std::string> items = split_text(text);
        for (const std::string& item : items)
            if (!contains(spec.choices, item))
                throw HostError(what + ": unknown item '" + item + "' (expected a list of " +
                                OIIO::Strutil::join(spec.choices, ", ") + ", or " +
                                OIIO::Strutil::join(spec.keywords, " or ") + ")");
        return items;
    }
    }
    throw HostError(what + ": unsupported modifier type");
}

// Parses and checks the declared range: "--denoise: radius must be in [0, 1000], got -1".
statmc::ParameterValue parse_value(const std::string& command, const ModifierSpec& spec,
                                   const std::string& text)
{
    statmc::ParameterValue value = parse_text(command, spec, text);
    double number = 0;
    if (const int* i = std::get_if<int>(&value))
        number = *i;
    else if (const double* d = std::get_if<double>(&value))
        number = *d;
    else
        return value;
    if (const std::string why = spec.range.violation(spec.name, number); !why.empty())
        throw HostError(command + ": " + why);
    return value;
}

}  // namespace

void Modifiers::require(const std::string& name) const
{
    if (!values_.has(name))
        throw HostError("modifier '" + name + "' has no value");
}

int Modifiers::get_int(const std::string& name) const
{
    require(name);
    return values_.get_int(name);
}

double Modifiers::get_float(const std::string& name) const
{
    require(name);
    return values_.get_float(name);
}

bool Modifiers::get_bool(const std::string& name) const
{
    require(name);
    return values_.get_bool(name);
}

std::string Modifiers::get_string(const std::string& name) const
{
    require(name);
    return values_.get_string(name);
}

std::vector<std::string> Modifiers::get_list(const std::string& name) const
{
    require(name);
    return values_.get_list(name);
}

Modifiers Modifiers::parse(const std::string& command,
                           const std::vector<std::pair<std::string, std::string>>& given,
                           const std::vector<ModifierSpec>& specs)
{
    auto spec_of = [&](const std::string& name) -> const ModifierSpec* {
        for (const ModifierSpec& s : specs)
            if (s.name == name)
                return &s;
        return nullptr;
    };
    Modifiers m;
    for (const auto& [name, text] : given) {
        const ModifierSpec* spec = spec_of(name);
        if (!spec) {
            std::vector<std::string> known;
            for (const ModifierSpec& s : specs)
                known.push_back(s.name);
            throw HostError(command + ": unknown modifier '" + name + "' (" +
                            (known.empty() ? std::string("it takes no modifiers")
                                           : "modifiers: " + OIIO::Strutil::join(known, ", ")) +
                            ")");
        }
        if (m.has(name))
            throw HostError(command + ": modifier '" + name + "' given twice");
        m.values_.set(name, parse_value(command, *spec, text));
    }
    for (const ModifierSpec& spec : specs)
        if (!m.has(spec.name) && !spec.default_value.empty())
            m.values_.set(spec.name, parse_value(command, spec, spec.default_value));
    return m;
}

}  // namespace statmc::host
