// The binary contract between a host and a plugin module: a shared library built with
// add_library(... MODULE ...) exporting three C symbols,
//
//   int  statmc_plugin_interface_version();                      // == kPluginInterfaceVersion
//   statmc::BuildIdentity statmc_plugin_build_identity();         // build_identity.h
//   void statmc_register_plugin(statmc::PluginRegistry&);
//
// The C++ types crossing the boundary (PluginRegistry, OperatorSpec, OIIO::ImageBuf)
// have no stable ABI, so the version is bumped whenever any of them changes, and a host
// refuses a module built against another version, another OpenImageIO, another string
// ABI or other type layouts, before calling into it.
#pragma once

#include "statmc/plugin_sdk/build_identity.h"
#include "statmc/plugin_sdk/plugin_registry.h"

namespace statmc {

inline constexpr int kPluginInterfaceVersion = 3;

}  // namespace statmc

#define STATMC_PLUGIN_VISIBLE extern "C" __attribute__((visibility("default")))

/// The one export line of a plugin: STATMC_EXPORT_PLUGIN(register_my_operators), where
/// `void register_my_operators(statmc::PluginRegistry&)` adds the module's operators.
#define STATMC_EXPORT_PLUGIN(register_function)                                                    \
    STATMC_PLUGIN_VISIBLE int statmc_plugin_interface_version()                                    \
    {                                                                                              \
        return statmc::kPluginInterfaceVersion;                                                    \
    }                                                                                              \
    STATMC_PLUGIN_VISIBLE statmc::BuildIdentity statmc_plugin_build_identity()                     \
    {                                                                                              \
        return statmc::this_build_identity();                                                      \
    }                                                                                              \
    STATMC_PLUGIN_VISIBLE void statmc_register_plugin(statmc::PluginRegistry& reg)                 \
    {                                                                                              \
        register_function(reg);                                                                    \
    }
