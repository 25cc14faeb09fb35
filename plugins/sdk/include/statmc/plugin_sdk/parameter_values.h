// The parsed, checked parameters of one operator invocation, read by the plugin with
// typed getters and defaults (Mitsuba's `props.get<float>("alpha", 0.005f)`).
#pragma once

#include <map>
#include <string>
#include <variant>
#include <vector>

namespace statmc {

using ParameterValue = std::variant<bool, int, double, std::string, std::vector<std::string>>;

class ParameterValues {
public:
    void set(const std::string& name, ParameterValue value) { values_[name] = std::move(value); }
    bool has(const std::string& name) const { return values_.count(name) != 0; }

    // The value of `name`, or `fallback` when it was neither given nor defaulted. A value
    // of another type is a programming error and throws std::bad_variant_access.
    bool get_bool(const std::string& name, bool fallback = false) const;
    int get_int(const std::string& name, int fallback = 0) const;
    double get_float(const std::string& name, double fallback = 0) const;
    std::string get_string(const std::string& name, const std::string& fallback = {}) const;
    std::vector<std::string> get_list(const std::string& name,
                                      const std::vector<std::string>& fallback = {}) const;

    /// The value of `name` as a command line spells it (bools 1/0, lists comma-separated,
    /// numbers in their shortest exact form); throws std::out_of_range when absent.
    std::string text(const std::string& name) const;

    /// The stored value itself; throws std::out_of_range when absent.
    const ParameterValue& at(const std::string& name) const { return values_.at(name); }

private:
    template <class T>
    T get(const std::string& name, const T& fallback) const
    {
        const auto it = values_.find(name);
        return it == values_.end() ? fallback : std::get<T>(it->second);
    }
    std::map<std::string, ParameterValue> values_;
};

}  // namespace statmc
