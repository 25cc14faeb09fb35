// Typed command modifiers, `--command:name=value:name2=value2`, as oiiotool spells them.
// Each command declares its modifiers; values are parsed and checked before anything runs.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace statmc::tool {

enum class ModifierType {
    Int,
    Float,
    Choice,  ///< one of `choices`
    List,    ///< comma-separated items from `choices`, or one of `keywords` alone
    String,
};

struct ModifierSpec {
    std::string name;
    ModifierType type = ModifierType::String;
    std::string default_value;  ///< empty: absent unless given
    std::string help;
    std::vector<std::string> choices;
    std::vector<std::string> keywords;  ///< List only: values that stand alone ("auto")

    /// "int", "float", "auto|boxcox|untransformed", "albedo,normal|auto|none", "name"
    std::string value_syntax() const;
};

/// The modifiers of one invocation, defaults filled in, each parsed to its type.
class Modifiers {
public:
    using Value = std::variant<int, double, std::string, std::vector<std::string>>;

    bool has(const std::string& name) const { return values_.count(name) != 0; }
    int get_int(const std::string& name) const;
    double get_float(const std::string& name) const;
    const std::string& get_string(const std::string& name) const;
    const std::vector<std::string>& get_list(const std::string& name) const;

    /// Parses `given` (name, text) pairs of command `command` against `specs`. Throws
    /// ToolError naming the command and modifier for an unknown or repeated modifier
    /// and for a malformed value.
    static Modifiers parse(const std::string& command,
                           const std::vector<std::pair<std::string, std::string>>& given,
                           const std::vector<ModifierSpec>& specs);

private:
    const Value& at(const std::string& name) const;
    std::map<std::string, Value> values_;
};

}  // namespace statmc::tool
