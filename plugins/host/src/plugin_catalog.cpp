#include "statmc/plugin_host/plugin_catalog.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <system_error>

#include <dlfcn.h>
#include <sys/auxv.h>

#include "statmc/plugin_host/help_text.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_sdk/plugin_loader.h"

namespace statmc::host {

namespace fs = std::filesystem;

namespace {

// The shared object holding this code when it is not the main program (the Python
// module), else empty. glibc's dladdr names the main program by its argv[0], which is no
// path to it, so the main program is recognised by its entry point's load base.
fs::path host_module()
{
    Dl_info here{}, main_program{};
    if (!::dladdr(reinterpret_cast<void*>(&host_module), &here) || !here.dli_fname ||
        !::dladdr(reinterpret_cast<void*>(::getauxval(AT_ENTRY)), &main_program) ||
        here.dli_fbase == main_program.dli_fbase)
        return {};
    std::error_code ec;
    const fs::path module = fs::absolute(here.dli_fname, ec);
    return ec ? fs::path() : module;
}

// Relative to the running program, so that a build tree or an installed prefix can be
// moved as a whole: PREFIX/bin/statmc finds PREFIX/lib/statmc/plugins (and a build tree's
// statmc its plugins/ beside it), and the Python module at
// PREFIX/lib/pythonX.Y/*-packages/statmc finds PREFIX/lib/statmc/plugins. The build tree's
// directory is only a fallback for programs that do not sit beside the modules (the tests,
// the Python module in the build tree).
std::vector<std::string> shipped_plugin_dirs()
{
    std::error_code ec;
    std::vector<fs::path> candidates;
    if (const fs::path module = host_module(); !module.empty()) {
        candidates = {module.parent_path() / ".." / ".." / ".." / "statmc" / "plugins"};
    } else {
        const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
        if (!ec)
            candidates = {exe.parent_path() / "plugins",
                          exe.parent_path() / ".." / "lib" / "statmc" / "plugins"};
    }
    std::vector<std::string> dirs;
    for (const fs::path& dir : candidates)
        if (fs::is_directory(dir, ec))
            dirs.push_back(dir.lexically_normal().string());
#ifdef STATMC_BUILD_PLUGIN_DIR
    if (dirs.empty() && fs::is_directory(STATMC_BUILD_PLUGIN_DIR, ec))
        dirs.push_back(STATMC_BUILD_PLUGIN_DIR);
#endif
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
