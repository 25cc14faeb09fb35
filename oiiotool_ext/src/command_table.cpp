#include "statmc/tool/command_table.h"

#include <algorithm>
#include <sstream>

#include "statmc/plugin_host/help_text.h"
#include "statmc/tool/plugin_commands.h"

namespace statmc::tool {

namespace {

std::string usage_of(const Command& c)
{
    std::string usage = c.name;
    if (!c.modifiers.empty())
        usage += "[:mod=val...]";
    for (const std::string& arg : c.arg_names)
        usage += " " + arg;
    if (!c.optional_arg_name.empty())
        usage += " [" + c.optional_arg_name + "]";
    return usage;
}

void describe(std::ostringstream& os, const Command& c)
{
    os << host::help_line("  " + usage_of(c), 32, c.summary);
    for (const std::string& alias : c.aliases)
        os << host::help_line("", 32, "(also " + alias + ")");
    // The left column shows the default as oiiotool's help does: ":radius=20".
    for (const host::ModifierSpec& m : c.modifiers) {
        const std::string shown = m.default_value.empty() ? m.value_syntax() : m.default_value;
        const std::string range = m.range.empty() ? "" : " " + m.range.text();
        os << host::help_line("      :" + m.name + "=" + shown, 32,
                              "(" + m.value_syntax() + range + ") " + m.help);
    }
}

}  // namespace

const std::vector<Command>& command_table()
{
    // In the order --help shows them.
    static const std::vector<Command> table = {
        input_command(),        output_command(),        data_format_command(),
        compression_command(),  all_subimages_command(), ch_command(),
        chnames_command(),      chappend_command(),      subimage_command(),
        siappend_command(),     dup_command(),           add_command(),
        sub_command(),          mul_command(),           addc_command(),
        mulc_command(),         colorconfig_command(),   colorconvert_command(),
        ociodisplay_command(),  crop_command(),          resize_command(),
        info_command(),         verbose_command(),       stats_command(),
        diff_command(),         echo_command(),          threads_command(),
        max_memory_command(),   check_inputs_command(),  frames_command(),
        skip_missing_command(), list_ops_command(),      help_command(),
        validate_command(),     version_command(),
    };
    return table;
}

const Command* find_command(std::string_view name)
{
    for (const Command& c : command_table())
        if (c.name == name ||
            std::find(c.aliases.begin(), c.aliases.end(), name) != c.aliases.end())
            return &c;
    for (const Command& c : plugin_commands())
        if (c.name == name)
            return &c;
    return nullptr;
}

std::string version_text() { return std::string("statmc ") + STATMC_VERSION + "\n"; }

std::string help_text()
{
    std::ostringstream os;
    os << "statmc " << STATMC_VERSION
       << " - statistical Monte Carlo denoising (Sakai et al. 2024)\n\n"
          "Usage: statmc [INPUT | COMMAND]...\n\n"
          "Arguments are read left to right on an image stack, as oiiotool reads them: an\n"
          "input file is pushed, a command pops its operands and pushes its result, and -o\n"
          "writes the top image. Modifiers follow a command: --name:mod=value:mod2=value.\n"
          "oiiotool's commands below behave as in oiiotool 2.4; the others it knows are\n"
          "refused by name.\n"
          "Images hold per-pixel statistics as EXR layers (docs/exr-layers.md).\n\n"
          "Commands:\n";
    for (const Command& c : command_table())
        describe(os, c);
    os << "\nOperators (plugins; statmc --help OP for details):\n";
    for (const Command& c : plugin_commands())
        describe(os, c);
    os << "\nExamples:\n"
          "  statmc in.exr --denoise:radius=20:alpha=0.005:guides=albedo,normal -o out.exr\n"
          "  statmc a.exr b.exr c.exr --passes --denoise -o out.exr\n"
          "  statmc task1.exr task2.exr task3.exr --merge -o frame.exr\n"
          "  statmc out.exr reference.exr --compare -o error.exr\n"
          "  statmc aovs.exr --denoise:aov=diffuse --denoise:aov=specular -o out.exr\n"
          "  statmc frame.exr --ch R,G,B --resize 50% -d half -o preview.exr   (oiiotool's "
          "commands)\n";
    return os.str();
}

}  // namespace statmc::tool
