// -i, -o and the settings for the reads and writes that follow (--max-memory,
// --check-inputs, -d, --compression): images between files and the stack.
#include <cctype>
#include <cstdint>
#include <optional>
#include <utility>

#include "channel_selection.h"
#include "image_report.h"
#include <OpenImageIO/imagebufalgo.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/storage_rules.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/number_parsing.h"
#include "statmc/tool/command_table.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

// OpenEXR stores half, float and uint32 channels; -d names one of them.
OIIO::TypeDesc exr_type(const std::string& name, const std::string& command)
{
    if (name.find('=') != std::string::npos)
        throw host::HostError(command + " " + name +
                              ": per-channel types (-d CHAN=TYPE) are an oiiotool feature that "
                              "statmc does not support");
    if (name == "half" || name == "float")
        return OIIO::TypeDesc(name);
    if (name == "uint32")  // oiiotool's spelling; it refuses "uint"
        return OIIO::TypeDesc::UINT32;
    throw host::HostError(command + ": OpenEXR stores half, float or uint32 channels, got '" +
                          name + "'");
}

// A lossy codec would bias every later test on the statistics, so it is refused rather
// than quietly replaced (docs/exr-layers.md, "File shape").
void check_compression(const std::string& name, const std::string& command)
{
    if (!layers::is_lossless_compression(name))
        throw host::HostError(command + ": '" + name +
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

// -o:keep=means: `image` without its statistics channels.
OIIO::ImageBuf without_statistics(const OIIO::ImageBuf& image, const Invocation& inv, int nthreads)
{
    std::vector<int> kept;
    for (int c = 0; c < image.nchannels(); ++c)
        if (!layers::is_any_statistics_channel(image.spec().channelnames[c]))
            kept.push_back(c);
    if (kept.empty())
        throw host::HostError(inv.name + ":keep=means " + inv.args[0] +
                              ": the image holds only statistics channels");
    OIIO::ImageBuf out;
    if (!OIIO::ImageBufAlgo::channels(out, image, int(kept.size()), kept, {}, {}, false, nthreads))
        throw host::HostError(inv.name + " " + inv.args[0] + ": " + out.geterror());
    return out;
}

// "16G", "512M", "1.5G", "100000K" or plain bytes, as a byte count > 0.
std::uint64_t byte_size(const std::string& text, const std::string& command)
{
    static const std::pair<char, double> units[] = {
        {'K', 1e3}, {'M', 1e6}, {'G', 1e9}, {'T', 1e12}};
    double scale = 1;
    std::string number = text;
    for (const auto& [suffix, factor] : units)
        if (!number.empty() && std::toupper(static_cast<unsigned char>(number.back())) == suffix) {
            scale = factor;
            number.pop_back();
        }
    const std::optional<double> value = host::try_parse_float(number);
    if (!value || !(*value > 0) || *value * scale > 1e18)
        throw host::HostError(
            command + ": expected a size such as 16G, 512M or a byte count, got '" + text + "'");
    return std::uint64_t(*value * scale);
}

}  // namespace

Command max_memory_command()
{
    Command c;
    c.name = "--max-memory";
    c.arg_names = {"SIZE"};
    c.summary = "Refuse to read an image whose header declares more than SIZE bytes of float "
                "pixels (16G, 512M, ...) [default: half of this machine's memory]";
    c.check = [](const Invocation& inv) { byte_size(inv.args[0], inv.name); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        ctx.input.max_memory = byte_size(inv.args[0], inv.name);
    };
    return c;
}

Command check_inputs_command()
{
    Command c;
    c.name = "--check-inputs";
    c.arg_names = {"0|1"};
    c.summary = "Check each OpenEXR input with OpenEXR's own file checker before reading it "
                "(1, the default; it costs about 3.5x the read) or trust the files (0)";
    auto flag = [](const Invocation& inv) {
        const std::string& a = inv.args[0];
        if (a != "0" && a != "1")
            throw host::HostError(inv.name + ": expected 0 or 1, got '" + a + "'");
        return a == "1";
    };
    c.check = [flag](const Invocation& inv) { flag(inv); };
    c.run = [flag](ToolContext& ctx, const Invocation& inv) {
        ctx.input.check_structure = flag(inv);
    };
    return c;
}

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
        layers::MipLevels mip_levels;
        StackImage image{layers::read_image_subimages(path, ctx.input, &mip_levels), path};
        image.mip_levels = std::move(mip_levels);
        const FileSpecs file_specs = ctx.print_info || ctx.print_stats
                                         ? layers::read_image_headers(path, ctx.input)
                                         : FileSpecs();
        if (ctx.print_info || ctx.print_stats)
            print_info(ctx.out, image, file_specs,
                       ctx.print_info && (ctx.verbose || ctx.info_verbose), ctx.all_subimages);
        if (ctx.print_stats)
            print_all_stats(ctx.out, image, file_specs, ctx.all_subimages, ctx.nthreads);
        // Linked to its sequence only as read: a channel selection would differ from the
        // neighbours an operator reads.
        if (const auto it = ctx.sequence_inputs.find(path);
            it != ctx.sequence_inputs.end() && !inv.modifiers.has("ch")) {
            image.sequence = it->second.sequence;
            image.frame = it->second.frame;
        }
        if (inv.modifiers.has("ch")) {
            auto keep_channels = [&](OIIO::ImageBuf& buf) {
                buf = select_channels(buf, inv.modifiers.get_string("ch"), path + ": -i:ch",
                                      ctx.nthreads);
                if (buf.has_error())
                    throw host::HostError(path + ": -i:ch: " + buf.geterror());
            };
            for (OIIO::ImageBuf& sub : image.subimages)
                keep_channels(sub);
            for (std::vector<OIIO::ImageBuf>& levels : image.mip_levels)
                for (OIIO::ImageBuf& level : levels)
                    keep_channels(level);
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
    c.modifiers = {
        statmc::string_parameter("type", "", "pixel type: half, float or uint32"),
        statmc::string_parameter("datatype", "", "the same as type"),
        statmc::choice_parameter("keep", {"all", "means"}, "all",
                                 "all channels, or only the means: R,G,B,A, guides, AOV means and "
                                 "diagnostics, without the statistics layers (variance, Box-Cox, "
                                 "moments, sampleCount), for a file only a compositor will see")};
    c.check = [](const Invocation& inv) { output_type(inv); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        layers::WriteOptions options = ctx.output;
        if (const std::optional<OIIO::TypeDesc> type = output_type(inv))
            options.format = *type;
        if (ctx.verbose)
            ctx.out << "Writing " << inv.args[0] << "\n";
        const StackImage& image = ctx.stack.top(inv.name);
        if (inv.modifiers.get_string("keep") == "all") {
            layers::write_image_file(image.subimages, inv.args[0], options, image.mip_levels);
            return;
        }
        layers::MipLevels levels = image.mip_levels;
        std::vector<OIIO::ImageBuf> subimages;
        for (std::size_t s = 0; s < image.subimages.size(); ++s) {
            subimages.push_back(without_statistics(image.subimages[s], inv, ctx.nthreads));
            if (s < levels.size())
                for (OIIO::ImageBuf& level : levels[s])
                    level = without_statistics(level, inv, ctx.nthreads);
        }
        layers::write_image_file(subimages, inv.args[0], options, levels);
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
