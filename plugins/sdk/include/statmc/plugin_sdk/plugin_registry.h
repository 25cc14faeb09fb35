// The operators known to a host. A plugin module's entry point adds to it; the host
// looks operators up by name and prints help from their specs.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "statmc/plugin_sdk/operator_spec.h"

namespace statmc {

/// A plugin could not be loaded or registered something invalid; the message names the
/// file (and operator) and is fit to show a user.
class PluginError : public std::runtime_error {
public:
    explicit PluginError(const std::string& message) : std::runtime_error(message) {}
};

class PluginRegistry {
public:
    /// Adds `op`, tagged with the module being loaded. Throws PluginError for an empty
    /// name, a missing run function, or a name already taken (naming both modules).
    void add(OperatorSpec op);

    const OperatorSpec* find(std::string_view name) const;
    const std::vector<OperatorSpec>& operators() const { return operators_; }

    /// The loader says which file the following add() calls come from.
    void set_current_module(std::string path) { current_module_ = std::move(path); }

private:
    std::vector<OperatorSpec> operators_;
    std::string current_module_;
};

}  // namespace statmc
