// Typed command modifiers, `--command:name=value:name2=value2`, as oiiotool spells them.
// Each command declares its modifiers with the plugin interface's ParameterSpec (so a
// plugin operator's declaration is used as is); values are parsed and type/range-checked
// before anything runs.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "statmc/plugin_sdk/parameter_spec.h"
#include "statmc/plugin_sdk/parameter_values.h"

namespace statmc::host {

using ModifierSpec = statmc::ParameterSpec;
using ModifierType = statmc::ParameterType;

/// The modifiers of one invocation, defaults filled in, each parsed to its type.
class Modifiers {
public:
    bool has(const std::string& name) const { return values_.has(name); }
    // These throw HostError when the modifier has no value (neither given nor defaulted).
    int get_int(const std::string& name) const;
    double get_float(const std::string& name) const;
    bool get_bool(const std::string& name) const;
    std::string get_string(const std::string& name) const;
    std::vector<std::string> get_list(const std::string& name) const;

    /// All values, as a plugin operator reads them.
    const statmc::ParameterValues& values() const { return values_; }

    /// Parses `given` (name, text) pairs of command `command` against `specs`. Throws
    /// HostError naming the command and modifier for an unknown or repeated modifier,
    /// a malformed value and a value outside the declared range.
    static Modifiers parse(const std::string& command,
                           const std::vector<std::pair<std::string, std::string>>& given,
                           const std::vector<ModifierSpec>& specs);

private:
    void require(const std::string& name) const;
    statmc::ParameterValues values_;
};

}  // namespace statmc::host
