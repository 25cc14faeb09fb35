// A module of the right interface version built "differently": another OpenImageIO and
// another ImageBuf layout. The host must refuse it, naming both, before registering it.
#include <cstdlib>

#include "statmc/plugin_sdk/plugin_interface.h"

STATMC_PLUGIN_VISIBLE int statmc_plugin_interface_version()
{
    return statmc::kPluginInterfaceVersion;
}

STATMC_PLUGIN_VISIBLE statmc::BuildIdentity statmc_plugin_build_identity()
{
    statmc::BuildIdentity identity = statmc::this_build_identity();
    identity.oiio_version += 100;  // the next minor version
    identity.sizeof_image_buf += 8;
    return identity;
}

STATMC_PLUGIN_VISIBLE void statmc_register_plugin(statmc::PluginRegistry&)
{
    std::abort();  // never reached: a refused module is not called
}
