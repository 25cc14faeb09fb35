// One directive's parameters, in the spirit of pbrt-v4's ParameterDictionary: the
// "type name" [values] pairs after a directive, typed lookups that remember which
// parameters were used, so that the rest can be reported as unknown, and the file:line
// every message about them names.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "statmc/render/scene_error.h"
#include "statmc/render/tokenizer.h"
#include "statmc/render/vec.h"

namespace statmc::render {

/// A number as messages show it: "5e+09", "2.5", "-1" (the stream's shortest form).
std::string number_text(double value);


/// One "type name" [values] parameter. Types are canonical (point3 → point, normal3 →
/// normal, color → rgb); string, texture and bool values are in `strings`, the others in
/// `numbers`.
struct Parameter {
    std::string type, name;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    int line = 0;       ///< where the "type name" declaration is
    bool used = false;  ///< looked up (or deliberately ignored) by the directive
};

class ParameterList {
public:
    /// The parameters of the directive at `file`:`line`.
    ParameterList(std::string file, int line, std::vector<Parameter> parameters = {});

    /// Reads the "type name" [values] pairs from tokens[pos] on, up to the first token that
    /// is not a quoted string, and leaves `pos` after them; `line` is the directive's.
    /// A malformed declaration, an unknown type, values of the wrong kind or a missing
    /// ']' is a SceneError naming file:line.
    static ParameterList parse(const std::vector<Token>& tokens, std::size_t& pos,
                               const std::string& file, int line);

    // Single values, marked used: nullopt when there is no parameter of that type and
    // name; a SceneError at the parameter's line when it has other than one value.
    std::optional<int> get_int(const std::string& name);      ///< "integer name"
    std::optional<float> get_float(const std::string& name);  ///< "float name"
    std::optional<bool> get_bool(const std::string& name);    ///< "bool name": "true" or "false"
    std::optional<std::string> get_string(const std::string& name);  ///< "string name"
    /// "rgb name" (three values). A spectrum, blackbody or xyz parameter of that name is a
    /// SceneError: only rgb colours are supported.
    std::optional<Rgb> get_rgb(const std::string& name);

    /// The first parameter "type name", marked used, for raw access to its values (arrays
    /// such as "point P" or "integer indices"); nullptr when absent.
    const Parameter* find(const std::string& type, const std::string& name);
    /// The first parameter called `name`, of any type, not marked used (for parameters
    /// whose mere presence is an error).
    const Parameter* find_any(const std::string& name) const;

    /// Marks every parameter called one of `names` (of any type) as used, so that it is not
    /// reported as unknown. With `warn_as`, each one also gives the warning
    /// `<warn_as> "<name>" not supported, ignored` at its line; the warnings are returned
    /// (names in the order given, then parameters in file order).
    std::vector<std::string> ignore(std::initializer_list<const char*> names,
                                    const std::optional<std::string>& warn_as = std::nullopt);

    /// `unknown parameter "<type> <name>" of <directive> ignored`, one warning for each
    /// parameter not used, in file order.
    std::vector<std::string> unused_warnings(const std::string& directive) const;

    /// Throws SceneError("file:line: what"); without a line, the directive's.
    [[noreturn]] void error(int line, const std::string& what) const;
    [[noreturn]] void error(const std::string& what) const { error(line_, what); }
    /// "file:line: warning: what"; without a line, the directive's.
    std::string warning(int line, const std::string& what) const;
    std::string warning(const std::string& what) const { return warning(line_, what); }

    const std::string& file() const { return file_; }
    int line() const { return line_; }  ///< the directive's
    const std::vector<Parameter>& parameters() const { return params_; }

private:
    std::string file_;
    int line_;
    std::vector<Parameter> params_;

    std::optional<double> get_number(const std::string& type, const std::string& name);
};

}  // namespace statmc::render
