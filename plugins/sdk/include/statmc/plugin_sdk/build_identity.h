// What a module and its host must share beyond the interface version for C++ types to
// cross the boundary safely: the same OpenImageIO, the same libstdc++ string ABI and the
// same layout of every type passed across. A plain C struct, so that a host can read a
// module's identity before trusting any C++ type the module was built with.
#pragma once

#include <string>

namespace statmc {

struct BuildIdentity {
    int oiio_version;  ///< OIIO_VERSION: 10000·major + 100·minor + patch
    int cxx11_abi;     ///< _GLIBCXX_USE_CXX11_ABI (std::string's layout)
    int sizeof_string;
    int sizeof_image_buf;
    int sizeof_image_spec;
    int sizeof_parameter_spec;
    int sizeof_parameter_values;
    int sizeof_operator_spec;
    int sizeof_run_context;
    int sizeof_plugin_registry;
};

/// The identity of the code that includes this header: the host's, or the module's.
BuildIdentity this_build_identity();

/// "" when `module` matches `host`, else what differs, both values named, e.g.
/// "OpenImageIO 2.5.0 (this statmc: 2.4.7)" or "sizeof(OIIO::ImageBuf) 24 (this statmc: 16)".
std::string build_identity_mismatch(const BuildIdentity& module, const BuildIdentity& host);

}  // namespace statmc

// this_build_identity() must be compiled in each binary (module and host), so it is
// defined inline here rather than in the SDK library.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/oiioversion.h>

#include "statmc/plugin_sdk/operator_spec.h"
#include "statmc/plugin_sdk/plugin_registry.h"

inline statmc::BuildIdentity statmc::this_build_identity()
{
    return {OIIO_VERSION,
            _GLIBCXX_USE_CXX11_ABI,
            int(sizeof(std::string)),
            int(sizeof(OIIO::ImageBuf)),
            int(sizeof(OIIO::ImageSpec)),
            int(sizeof(ParameterSpec)),
            int(sizeof(ParameterValues)),
            int(sizeof(OperatorSpec)),
            int(sizeof(RunContext)),
            int(sizeof(PluginRegistry))};
}
