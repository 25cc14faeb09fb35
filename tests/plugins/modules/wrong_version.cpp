// A module built against "another" interface version: the host must refuse it before
// calling its registration function (which would otherwise misread the registry).
#include <cstdlib>

#include "statmc/plugin_sdk/plugin_interface.h"

STATMC_PLUGIN_VISIBLE int statmc_plugin_interface_version()
{
    return statmc::kPluginInterfaceVersion + 41;
}

STATMC_PLUGIN_VISIBLE void statmc_register_plugin(statmc::PluginRegistry&)
{
    std::abort();  // never reached: a refused module is not called
}
