#include "statmc/plugin_host/plugin_catalog.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <system_error>

#include "statmc/layers/shipped_files.h"
#include "statmc/plugin_host/help_text.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_sdk/plugin_loader.h"

namespace statmc::host {

namespace fs = std::filesystem;

namespace {

// The shipped modules' directory (layers/shipped_files.h); the build tree's is only a
// fallback for programs that do not sit beside the modules (the tests, the Python module
// in the build tree).
std::vector<std::string> shipped_plugin_dirs()
{
    std::vector<std::string> dirs;
    std::error_code ec;
    for (const std::string& dir : statmc::layers::shipped_paths("plugins", STATMC_BUILD_PLUGIN_DIR))
        if (fs::is_directory(dir, ec))
            dirs.push_back(dir);
    return dirs;
}

statmc::PluginRegistry load_registry()
{
    statmc::PluginRegistry registry;
    try {
        for (const std::string& dir : plugin_search_path())
            for (const std::string& file : statmc::plugin_files(dir))
                statmc::load_plugin(file, registry);
    } catch (const statmc::PluginError& e) {
        throw HostError(e.what());
    }
    return registry;
}

// `text` word-wrapped, each line indented by two spaces.
std::string wrapped(const std::string& text) { return help_line("", 2, text); }

}  // namespace

std::string input_text(const statmc::OperatorSpec& op)
{
    if (op.inputs == statmc::kVariadicInputs)
        return std::to_string(op.min_inputs) + "+ " + op.input_noun;
    return std::to_string(op.inputs) + (op.inputs == 1 ? " image" : " images");
}

std::vector<std::string> plugin_search_path()
{
    std::vector<std::string> dirs = shipped_plugin_dirs();
    std::vector<fs::path> seen;
    for (const std::string& dir : dirs)
        seen.push_back(fs::weakly_canonical(dir));
    // A directory named twice (say, the shipped one on $STATMC_PLUGIN_PATH too) is searched
    // once, rather than failing on its modules' names being taken.
    if (const char* env = std::getenv("STATMC_PLUGIN_PATH"))
        for (const std::string& dir : statmc::split_search_path(env)) {
            std::error_code ec;
            const fs::path canonical = fs::weakly_canonical(dir, ec);
            if (std::find(seen.begin(), seen.end(), canonical) != seen.end())
                continue;
            seen.push_back(canonical);
            dirs.push_back(dir);
        }
    return dirs;
}

const statmc::PluginRegistry& plugin_registry()
{
    static const statmc::PluginRegistry registry = load_registry();
    return registry;
}

std::string operator_list_text()
{
    std::ostringstream os;
    for (const statmc::OperatorSpec& op : plugin_registry().operators())
        os << "  " << std::left << std::setw(14) << ("--" + op.name) << std::setw(22)
           << input_text(op) << op.summary << "\n";
    return os.str();
}

std::string operator_help_text(std::string_view name)
{
    if (name.rfind("--", 0) == 0)
        name.remove_prefix(2);
    const statmc::OperatorSpec* op = plugin_registry().find(name);
    if (!op)
        throw HostError("--help: unknown operator '" + std::string(name) +
                        "' (see statmc --list-ops)");
    std::ostringstream os;
    os << "--" << op->name << (op->parameters.empty() ? "" : "[:name=value...]") << "   ("
       << input_text(*op) << ")\n"
       << wrapped(op->summary) << "\n"
       << wrapped(op->help);
    if (!op->parameters.empty()) {
        // The name column fits the longest name, so that none runs into its type.
        std::size_t name_width = std::string("parameter").size();
        for (const statmc::ParameterSpec& p : op->parameters)
            name_width = std::max(name_width, p.name.size());
        const int names = int(name_width) + 2;
        os << "\n  " << std::left << std::setw(names) << "parameter" << std::setw(8) << "type"
           << std::setw(10) << "default" << std::setw(12) << "range"
           << "meaning\n";
        for (const statmc::ParameterSpec& p : op->parameters)
            os << "  " << std::setw(names) << p.name << std::setw(8) << statmc::type_name(p.type)
               << std::setw(10) << (p.default_value.empty() ? "-" : p.default_value)
               << std::setw(12) << (p.range.empty() ? "-" : p.range.text()) << p.help
               << (p.choices.empty() ? "" : " (" + p.value_syntax() + ")") << "\n";
    }
    os << "\n  from " << op->module << "\n";
    return os.str();
}

}  // namespace statmc::host
