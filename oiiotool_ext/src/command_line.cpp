#include "statmc/tool/command_line.h"

#include "oiiotool_commands.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/text_split.h"
#include "statmc/tool/command_table.h"

namespace statmc::tool {

namespace {

bool is_command_word(const std::string& word) { return word.size() > 1 && word[0] == '-'; }

// oiiotool treats one and two dashes alike ("-resize" is "--resize"): the two-dash
// spelling of a one-dash name, else the name itself.
std::string two_dash(const std::string& name)
{
    return name.size() > 2 && name[1] != '-' ? "-" + name : name;
}

const Command* find_either_spelling(std::string& name)
{
    if (const Command* c = find_command(name))
        return c;
    const std::string dashed = two_dash(name);
    if (dashed != name)
        if (const Command* c = find_command(dashed)) {
            name = dashed;
            return c;
        }
    return nullptr;
}

[[noreturn]] void unknown_command(const std::string& name)
{
    if (is_oiiotool_command(name) || is_oiiotool_command(two_dash(name)))
        throw host::HostError(name +
                              " is an oiiotool command that statmc does not support (run that "
                              "step with oiiotool; statmc --help lists the supported ones)");
    throw host::HostError("unknown command '" + name + "' (see statmc --help)");
}

// oiiotool would evaluate {expressions}; passing them on literally would differ silently.
void refuse_expression(const std::string& word)
{
    const std::size_t open = word.find('{');
    if (open != std::string::npos && word.find('}', open) != std::string::npos)
        throw host::HostError("'" + word + "': statmc does not evaluate oiiotool's {expressions}");
}

}  // namespace

std::pair<std::string, std::vector<std::pair<std::string, std::string>>>
split_command(const std::string& word)
{
    std::vector<std::string> parts = host::split_text(word, ':');
    std::vector<std::pair<std::string, std::string>> modifiers;
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const std::string& part = parts[i];
        const std::size_t eq = part.find('=');
        if (part.empty())
            throw host::HostError(parts[0] + ": empty modifier in '" + word + "'");
        if (eq == std::string::npos || eq == 0)
            throw host::HostError(parts[0] + ": modifier '" + part +
                                  "' is not of the form name=value");
        modifiers.emplace_back(part.substr(0, eq), part.substr(eq + 1));
    }
    return {parts[0], modifiers};
}

Invocation parse_invocation(const std::vector<std::string>& args, std::size_t& i)
{
    const std::string& word = args[i++];
    refuse_expression(word);
    if (word == "-")
        throw host::HostError("'-': statmc cannot read images from standard input");
    Invocation inv;
    if (!is_command_word(word)) {
        // oiiotool's rule: a bare argument is an input file.
        inv.command = find_command("-i");
        inv.name = "-i";
        inv.args = {word};
        return inv;
    }
    auto [name, given] = split_command(word);
    inv.command = find_either_spelling(name);
    if (!inv.command)
        unknown_command(name);
    inv.name = name;
    inv.modifiers = host::Modifiers::parse(name, given, inv.command->modifiers);
    for (const std::string& arg_name : inv.command->arg_names) {
        if (i >= args.size())
            throw host::HostError(name + ": missing argument " + arg_name);
        refuse_expression(args[i]);
        inv.args.push_back(args[i++]);
    }
    if (!inv.command->optional_arg_name.empty() && i < args.size())
        inv.args.push_back(args[i++]);
    return inv;
}

std::vector<Invocation> parse_program(const std::vector<std::string>& args)
{
    std::vector<Invocation> program;
    for (std::size_t i = 0; i < args.size();) {
        program.push_back(parse_invocation(args, i));
        const Invocation& inv = program.back();
        if (inv.command->immediate) {
            // --validate checks what comes before it: anything after would go unchecked.
            if (inv.command->name == "--validate" && i < args.size())
                throw host::HostError("--validate checks the commands before it: put it last, not "
                                      "before '" +
                                      args[i] + "'");
            break;
        }
        if (inv.command->check)
            inv.command->check(inv);
    }
    return program;
}

}  // namespace statmc::tool
