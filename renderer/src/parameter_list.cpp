#include "statmc/render/parameter_list.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace statmc::render {

std::string number_text(double value)
{
    std::ostringstream text;
    text << value;
    return text.str();
}


ParameterList::ParameterList(std::string file, int line, std::vector<Parameter> parameters)
    : file_(std::move(file)), line_(line), params_(std::move(parameters))
{
}

ParameterList ParameterList::parse(const std::vector<Token>& tokens, std::size_t& pos,
                                   const std::string& file, int line)
{
    ParameterList out(file, line);
    auto at_end = [&] { return pos >= tokens.size(); };
    while (!at_end() && tokens[pos].kind == Token::Kind::String) {
        const Token& decl = tokens[pos++];
        std::istringstream ss(decl.text);
        Parameter p;
        p.line = decl.line;
        if (!(ss >> p.type >> p.name))
            out.error(decl.line, "malformed parameter declaration \"" + decl.text +
                                     "\" (expected \"type name\")");
        if (p.type == "point3")
            p.type = "point";
        if (p.type == "normal3")
            p.type = "normal";
        if (p.type == "color")
            p.type = "rgb";
        static const char* known[] = {"integer", "float",    "point2",    "vector2", "point",
                                      "vector",  "normal",   "rgb",       "bool",    "string",
                                      "texture", "spectrum", "blackbody", "xyz"};
        bool ok = false;
        for (const char* k : known)
            ok = ok || p.type == k;
        if (!ok)
            out.error(decl.line,
                      "unknown parameter type '" + p.type + "' in \"" + decl.text + "\"");
        const bool is_text = p.type == "string" || p.type == "texture" || p.type == "bool";
        auto value = [&] {
            if (at_end())
                out.error(decl.line, "parameter \"" + decl.text + "\" has no value");
            const Token& t = tokens[pos++];
            if (is_text) {
                if (t.kind != Token::Kind::String)
                    out.error(t.line, "parameter \"" + decl.text + "\" expects quoted strings");
                p.strings.push_back(t.text);
            } else {
                if (t.kind != Token::Kind::Number)
                    out.error(t.line, "parameter \"" + decl.text + "\" expects numbers, got '" +
                                          t.text + "'");
                p.numbers.push_back(t.number);
            }
        };
        if (!at_end() && tokens[pos].kind == Token::Kind::OpenBracket) {
            ++pos;
            while (!at_end() && tokens[pos].kind != Token::Kind::CloseBracket)
                value();
            if (at_end())
                out.error(decl.line, "missing ']' after parameter \"" + decl.text + "\"");
            ++pos;
        } else {
            value();
        }
        out.params_.push_back(std::move(p));
    }
    return out;
}

const Parameter* ParameterList::find(const std::string& type, const std::string& name)
{
    for (Parameter& p : params_)
        if (p.name == name && p.type == type) {
            p.used = true;
            return &p;
        }
    return nullptr;
}

const Parameter* ParameterList::find_any(const std::string& name) const
{
    for (const Parameter& p : params_)
        if (p.name == name)
            return &p;
    return nullptr;
}

std::optional<double> ParameterList::get_number(const std::string& type, const std::string& name)
{
    const Parameter* p = find(type, name);
    if (!p)
        return std::nullopt;
    if (p->numbers.size() != 1)
        error(p->line, "\"" + type + " " + name + "\" needs one value");
    return p->numbers[0];
}

std::optional<int> ParameterList::get_int(const std::string& name)
{
    const auto v = get_number("integer", name);
    if (!v)
        return std::nullopt;
    // A whole number an int holds: 2.5, NaN or 5e9 would be truncated or undefined.
    if (!(*v == std::floor(*v) && std::abs(*v) <= double(std::numeric_limits<int>::max()))) {
        error(find("integer", name)->line,
              "\"integer " + name + "\" needs a whole number that fits an int, got " +
                  number_text(*v));
    }
    return int(*v);
}

std::optional<float> ParameterList::get_float(const std::string& name)
{
    const auto v = get_number("float", name);
    return v ? std::optional<float>(float(*v)) : std::nullopt;
}

std::optional<bool> ParameterList::get_bool(const std::string& name)
{
    const Parameter* p = find("bool", name);
    if (!p)
        return std::nullopt;
    if (p->strings.size() != 1 || (p->strings[0] != "true" && p->strings[0] != "false"))
        error(p->line, "\"bool " + name + "\" must be \"true\" or \"false\"");
    return p->strings[0] == "true";
}

std::optional<std::string> ParameterList::get_string(const std::string& name)
{
    const Parameter* p = find("string", name);
    if (!p)
        return std::nullopt;
    if (p->strings.size() != 1)
        error(p->line, "\"string " + name + "\" needs one value");
    return p->strings[0];
}

std::optional<Rgb> ParameterList::get_rgb(const std::string& name)
{
    for (Parameter& p : params_)
        if (p.name == name && (p.type == "spectrum" || p.type == "blackbody" || p.type == "xyz")) {
            p.used = true;
            error(p.line,
                  "unsupported: \"" + p.type + " " + name + "\" (only rgb colours are supported)");
        }
    const Parameter* p = find("rgb", name);
    if (!p)
        return std::nullopt;
    if (p->numbers.size() != 3)
        error(p->line, "\"rgb " + name + "\" needs three values");
    return Rgb{float(p->numbers[0]), float(p->numbers[1]), float(p->numbers[2])};
}

std::vector<std::string> ParameterList::ignore(std::initializer_list<const char*> names,
                                               const std::optional<std::string>& warn_as)
{
    std::vector<std::string> warnings;
    for (const char* name : names)
        for (Parameter& p : params_)
            if (p.name == name) {
                p.used = true;
                if (warn_as)
                    warnings.push_back(
                        warning(p.line, *warn_as + " \"" + name + "\" not supported, ignored"));
            }
    return warnings;
}

std::vector<std::string> ParameterList::unused_warnings(const std::string& directive) const
{
    std::vector<std::string> warnings;
    for (const Parameter& p : params_)
        if (!p.used)
            warnings.push_back(warning(p.line, "unknown parameter \"" + p.type + " " + p.name +
                                                   "\" of " + directive + " ignored"));
    return warnings;
}

void ParameterList::error(int line, const std::string& what) const
{
    throw SceneError(file_ + ":" + std::to_string(line) + ": " + what);
}

std::string ParameterList::warning(int line, const std::string& what) const
{
    return file_ + ":" + std::to_string(line) + ": warning: " + what;
}

}  // namespace statmc::render
