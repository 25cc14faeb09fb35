#include "statmc/plugin_sdk/build_identity.h"

#include <vector>

namespace statmc {

namespace {

std::string oiio_text(int version)
{
    return std::to_string(version / 10000) + "." + std::to_string(version / 100 % 100) + "." +
           std::to_string(version % 100);
}

}  // namespace

std::string build_identity_mismatch(const BuildIdentity& module, const BuildIdentity& host)
{
    std::vector<std::string> found;
    auto differ = [&](const char* what, int m, int h, const std::string& m_text,
                      const std::string& h_text) {
        if (m != h)
            found.push_back(std::string(what) + m_text + " (this statmc: " + h_text + ")");
    };
    auto differ_size = [&](const char* type, int m, int h) {
        differ(type, m, h, " " + std::to_string(m), std::to_string(h));
    };
    differ("OpenImageIO ", module.oiio_version, host.oiio_version, oiio_text(module.oiio_version),
           oiio_text(host.oiio_version));
    differ("_GLIBCXX_USE_CXX11_ABI=", module.cxx11_abi, host.cxx11_abi,
           std::to_string(module.cxx11_abi), std::to_string(host.cxx11_abi));
    differ_size("sizeof(std::string)", module.sizeof_string, host.sizeof_string);
    differ_size("sizeof(OIIO::ImageBuf)", module.sizeof_image_buf, host.sizeof_image_buf);
    differ_size("sizeof(OIIO::ImageSpec)", module.sizeof_image_spec, host.sizeof_image_spec);
    differ_size("sizeof(statmc::ParameterSpec)", module.sizeof_parameter_spec,
                host.sizeof_parameter_spec);
    differ_size("sizeof(statmc::ParameterValues)", module.sizeof_parameter_values,
                host.sizeof_parameter_values);
    differ_size("sizeof(statmc::OperatorSpec)", module.sizeof_operator_spec,
                host.sizeof_operator_spec);
    differ_size("sizeof(statmc::RunContext)", module.sizeof_run_context, host.sizeof_run_context);
    differ_size("sizeof(statmc::PluginRegistry)", module.sizeof_plugin_registry,
                host.sizeof_plugin_registry);
    std::string text;
    for (const std::string& f : found)
        text += (text.empty() ? "" : ", ") + f;
    return text;
}

}  // namespace statmc
