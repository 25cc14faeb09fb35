#include "statmc/plugin_sdk/parameter_values.h"

#include <type_traits>

#include <OpenImageIO/strutil.h>

#include "statmc/plugin_sdk/parameter_spec.h"

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

std::string ParameterValues::text(const std::string& name) const
{
    return std::visit(
        [](const auto& v) -> std::string {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, bool>)
                return v ? "1" : "0";
            else if constexpr (std::is_same_v<T, int>)
                return std::to_string(v);
            else if constexpr (std::is_same_v<T, double>)
                return number_text(v);
            else if constexpr (std::is_same_v<T, std::string>)
                return v;
            else
                return OIIO::Strutil::join(v, ",");
        },
        values_.at(name));
}

}  // namespace statmc
