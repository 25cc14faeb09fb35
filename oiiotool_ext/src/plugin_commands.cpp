#include "statmc/tool/plugin_commands.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <system_error>

#include <dlfcn.h>
#include <sys/auxv.h>

#include "help_text.h"
#include "statmc/plugin_sdk/plugin_loader.h"
#include "statmc/tool/tool_error.h"
#include "tool_context.h"

namespace statmc::tool {

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
        throw ToolError(e.what());
    }
    return registry;
}

std::string input_text(const statmc::OperatorSpec& op)
{
    if (op.inputs == statmc::kVariadicInputs)
        return std::to_string(op.min_inputs) + "+ " + op.input_noun;
    return std::to_string(op.inputs) + (op.inputs == 1 ? " image" : " images");
}

std::size_t input_count(const statmc::OperatorSpec& op, const Invocation& inv,
                        const ToolContext& ctx)
{
    if (op.inputs != statmc::kVariadicInputs)
        return std::size_t(op.inputs);
    const std::size_t k =
        inv.modifiers.has("n") ? std::size_t(inv.modifiers.get_int("n")) : ctx.stack.size();
    if (const std::string why = op.input_count_problem(k); !why.empty())
        throw ToolError(inv.name + ": " + why);
    return k;
}

// Calls into a module. Operators report errors on their image and never throw, but a
// third-party one may: that becomes an error naming the operator and its module.
template <class Call>
auto guarded(const statmc::OperatorSpec& op, const std::string& where, Call&& call)
{
    const std::string culprit =
        "--" + op.name + " (" + (op.module.empty() ? "the host" : op.module) + ")";
    try {
        return call();
    } catch (const std::exception& e) {
        throw ToolError("--" + op.name + ": " + where + "the operator threw, which it must not: " +
                        e.what() + " [" + culprit + "]");
    } catch (...) {
        throw ToolError("--" + op.name + ": " + where +
                        "the operator threw a non-standard exception [" + culprit + "]");
    }
}

void run_operator(const statmc::OperatorSpec& op, ToolContext& ctx, const Invocation& inv)
{
    const std::size_t count = input_count(op, inv, ctx);
    std::vector<StackImage> popped = ctx.stack.pop(count, inv.name);
    std::vector<const OIIO::ImageBuf*> images;
    statmc::RunContext run_context;
    run_context.nthreads = ctx.nthreads;
    run_context.out = &ctx.out;
    run_context.module = op.module;
    for (const StackImage& s : popped) {
        images.push_back(&s.image());
        run_context.input_labels.push_back(s.label);
    }
    // The input as read, for the sequence to keep when it asks for its neighbours; in
    // place, the operator's own image until it writes.
    const OIIO::ImageBuf* centre = popped.empty() ? nullptr : &popped[0].image();
    if (popped.size() == 1 && popped[0].sequence) {
        run_context.sequence_frames = [&, seq = popped[0].sequence,
                                       frame = popped[0].frame](const std::vector<int>& offsets) {
            seq->remember(frame, *centre);
            return seq->around(frame, offsets, ctx.input);
        };
    }
    // One input is named in the message; several are named by the operator itself.
    const std::string where = popped.size() == 1 ? popped[0].label + ": " : "";
    StackImage result;
    if (op.run_in_place && popped.size() == 1) {
        // The popped image is the stack's own, so the operator may reuse it (statmc's
        // operators read subimage 0 and push a one-part image either way).
        OIIO::ImageBuf image = std::move(popped[0].subimages.front());
        centre = &image;
        guarded(op, where,
                [&] { return op.run_in_place(image, inv.modifiers.values(), run_context); });
        result = StackImage{std::move(image), ""};
    } else {
        result = StackImage{
            guarded(op, where, [&] { return op.run(images, inv.modifiers.values(), run_context); }),
            ""};
    }
    if (result.image().has_error())
        throw ToolError(inv.name + ": " + where + result.image().geterror());
    result.label =
        popped.size() == 1 ? popped[0].label + " (" + op.name + ")" : inv.name + " result";
    ctx.stack.push(std::move(result));
}

// `text` word-wrapped, each line indented by two spaces.
std::string wrapped(const std::string& text) { return help_line("", 2, text); }

}  // namespace

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

const std::vector<Command>& plugin_commands()
{
    static const std::vector<Command> commands = [] {
        std::vector<Command> list;
        for (const statmc::OperatorSpec& op : plugin_registry().operators())
            list.push_back(operator_command(op));
        return list;
    }();
    return commands;
}

Command operator_command(const statmc::OperatorSpec& op)
{
    Command c;
    c.name = "--" + op.name;
    c.summary = op.summary;
    c.modifiers = op.parameters;
    c.check = [op](const Invocation& inv) {
        if (op.check)
            if (const std::string why =
                    guarded(op, "", [&] { return op.check(inv.modifiers.values()); });
                !why.empty())
                throw ToolError(inv.name + ": " + why);
    };
    c.run = [op](ToolContext& ctx, const Invocation& inv) { run_operator(op, ctx, inv); };
    return c;
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
        throw ToolError("--help: unknown operator '" + std::string(name) +
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

}  // namespace statmc::tool
