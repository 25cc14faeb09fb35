#include "statmc/plugin_sdk/parameter_values.h"

namespace statmc {

bool ParameterValues::get_bool(const std::string& name, bool fallback) const
{
    return get<bool>(name, fallback);
}

int ParameterValues::get_int(const std::string& name, int fallback) const
{
    return get<int>(name, fallback);
}

double ParameterValues::get_float(const std::string& name, double fallback) const
{
    return get<double>(name, fallback);
}

std::string ParameterValues::get_string(const std::string& name, const std::string& fallback) const
{
    return get<std::string>(name, fallback);
}

std::vector<std::string> ParameterValues::get_list(const std::string& name,
                                                   const std::vector<std::string>& fallback) const
{
    return get<std::vector<std::string>>(name, fallback);
}

}  // namespace statmc
