#include "statmc/plugin_sdk/plugin_registry.h"

namespace statmc {

void PluginRegistry::add(OperatorSpec op)
{
    const std::string where = current_module_.empty() ? "" : current_module_ + ": ";
    if (op.name.empty())
        throw PluginError(where + "an operator without a name");
    if (!op.run)
        throw PluginError(where + "operator '" + op.name + "' has no run function");
    if (const OperatorSpec* other = find(op.name))
        throw PluginError(where + "operator '" + op.name + "' is already registered by " +
                          (other->module.empty() ? "the host" : other->module));
    op.module = current_module_;
    operators_.push_back(std::move(op));
}

const OperatorSpec* PluginRegistry::find(std::string_view name) const
{
    for (const OperatorSpec& op : operators_)
        if (op.name == name)
            return &op;
    return nullptr;
}

}  // namespace statmc
