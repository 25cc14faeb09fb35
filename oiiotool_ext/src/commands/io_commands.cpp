// -i, -o and the settings for the outputs that follow (-d, --compression): images
// between files and the stack.
#include <optional>

#include "channel_selection.h"
#include "image_report.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/storage_rules.h"
#include "statmc/tool/command_table.h"
#include "statmc/tool/tool_error.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

// OpenEXR stores half, float and uint32 channels; -d names one of them.
OIIO::TypeDesc exr_type(const std::string& name, const std::string& command)
{
    if (name.find('=') != std::string::npos)
        throw ToolError(command + " " + name +
                        ": per-channel types (-d CHAN=TYPE) are an oiiotool feature that "
                        "statmc does not support");
    if (name == "half" || name == "float")
        return OIIO::TypeDesc(name);
    if (name == "uint32")  // oiiotool's spelling; it refuses "uint"
        return OIIO::TypeDesc::UINT32;
    throw ToolError(command + ": OpenEXR stores half, float or uint32 channels, got '" + name +
                    "'");
}

// A lossy codec would bias every later test on the statistics, so it is refused rather
// than quietly replaced (docs/exr-layers.md, "File shape").
void check_compression(const std::string& name, const std::string& command)
{
    if (!layers::is_lossless_compression(name))
        throw ToolError(command + ": '" + name +
                        "' is lossy; statmc writes none, rle, zip, zips or piz");
}

// -o's :type= or :datatype= (the later one wins), if either is given.
std::optional<OIIO::TypeDesc> output_type(const Invocation& inv)
{
    std::optional<OIIO::TypeDesc> type;
    for (const char* m : {"type", "datatype"})
        if (inv.modifiers.has(m))
            type = exr_type(inv.modifiers.get_string(m), inv.name + ":" + m);
    return type;
}

}  // namespace

Command input_command()
{
    Command c;
    c.name = "-i";
    c.arg_names = {"FILE"};
    c.summary = "Read an image (every subimage) and push it on the stack (a bare FILE does "
                "the same); :ch= reads only the listed channels";
    // now= and type=float are accepted for oiiotool's scripts: statmc always reads at once,
    // in float.
    c.modifiers = {statmc::string_parameter("ch", "", "channels to keep, as --ch lists them"),
                   statmc::bool_parameter("now", true, "read at once (statmc always does)"),
                   statmc::choice_parameter("type", {"float"}, "float",
                                            "pixel type in memory (statmc always uses float)")};
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const std::string& path = inv.args[0];
        if (ctx.verbose)
            ctx.out << "Reading " << path << "\n";
        StackImage image{layers::read_image_subimages(path), path};
        if (ctx.print_info || ctx.print_stats)
            print_info(ctx.out, image, ctx.print_info && (ctx.verbose || ctx.info_verbose),
                       ctx.all_subimages);
        if (ctx.print_stats)
            print_all_stats(ctx.out, image, ctx.all_subimages, ctx.nthreads);
        if (inv.modifiers.has("ch"))
            for (OIIO::ImageBuf& sub : image.subimages) {
                sub = select_channels(sub, inv.modifiers.get_string("ch"), path + ": -i:ch",
                                      ctx.nthreads);
                if (sub.has_error())
                    throw ToolError(path + ": -i:ch: " + sub.geterror());
            }
        ctx.stack.push(std::move(image));
    };
    return c;
}

Command output_command()
{
    Command c;
    c.name = "-o";
    c.arg_names = {"FILE"};
    c.summary = "Write the top image (every subimage) to an OpenEXR file: float and lossless "
                "unless -d/:type= or --compression say otherwise; via a temporary file, so a "
                "failed write leaves no file";
    c.modifiers = {statmc::string_parameter("type", "", "pixel type: half, float or uint32"),
                   statmc::string_parameter("datatype", "", "the same as type")};
    c.check = [](const Invocation& inv) { output_type(inv); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        layers::WriteOptions options = ctx.output;
        if (const std::optional<OIIO::TypeDesc> type = output_type(inv))
            options.format = *type;
        if (ctx.verbose)
            ctx.out << "Writing " << inv.args[0] << "\n";
        layers::write_image_file(ctx.stack.top(inv.name).subimages, inv.args[0], options);
    };
    return c;
}

Command data_format_command()
{
    Command c;
    c.name = "-d";
    c.arg_names = {"TYPE"};
    c.summary = "Pixel type of the outputs that follow: half, float or uint32 (statmc's "
                "default is float, the layer contract's)";
    c.check = [](const Invocation& inv) { exr_type(inv.args[0], inv.name); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.output.format = exr_type(inv.args[0], inv.name);
    };
    return c;
}

Command compression_command()
{
    Command c;
    c.name = "--compression";
    c.arg_names = {"NAME"};
    c.summary = "Compression of the outputs that follow: none, rle, zip, zips or piz "
                "(default: the input's if lossless, else zip)";
    c.check = [](const Invocation& inv) { check_compression(inv.args[0], inv.name); };
    c.run = [](ToolContext& ctx, const Invocation& inv) { ctx.output.compression = inv.args[0]; };
    return c;
}

}  // namespace statmc::tool
