// --crop and --resize: the pixel data window, through ImageBufAlgo.
#include <cmath>
#include <cstdio>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_table.h"
#include "subimage_loop.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

struct Geometry {
    int width = 0, height = 0;
    bool has_origin = false;
    int x = 0, y = 0;
    double percent = 0;  ///< "N%": the size is N% of each image's, set by sized_for
};

[[noreturn]] void no_pixels(const std::string& text, const std::string& command)
{
    throw host::HostError(command + ": geometry '" + text + "' has no pixels");
}

// oiiotool's GEOM: "WxH", "WxH+X+Y" (signed offsets) or "xmin,ymin,xmax,ymax"
// (inclusive); with `allow_percent`, "N%" (sized per image by sized_for). Parsed once,
// in the command's check, so a bad GEOM fails before anything runs.
Geometry parse_geometry(const std::string& text, bool allow_percent, const std::string& command)
{
    Geometry g;
    char tail = 0;
    int xmin, ymin, xmax, ymax;
    double percent = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &xmin, &ymin, &xmax, &ymax, &tail) == 4 &&
        xmax >= xmin && ymax >= ymin) {
        g = {xmax - xmin + 1, ymax - ymin + 1, true, xmin, ymin};
    } else if (std::sscanf(text.c_str(), "%dx%d%d%d%c", &g.width, &g.height, &g.x, &g.y, &tail) ==
                   4 &&
               text.find_first_of("+-", text.find('x')) != std::string::npos) {
        g.has_origin = true;
    } else if (std::sscanf(text.c_str(), "%dx%d%c", &g.width, &g.height, &tail) == 2) {
    } else if (allow_percent && std::sscanf(text.c_str(), "%lf%%%c", &percent, &tail) == 1 &&
               percent > 0) {
        g.percent = percent;
        return g;
    } else {
        throw host::HostError(command + ": geometry '" + text + "' is not WxH, WxH+X+Y" +
                              (allow_percent ? ", N%" : "") + " or xmin,ymin,xmax,ymax");
    }
    if (g.width <= 0 || g.height <= 0)
        no_pixels(text, command);
    return g;
}

// `g` for an image whose display window is `full`: "N%" of its size (rounded).
Geometry sized_for(Geometry g, const OIIO::ROI& full, const std::string& text,
                   const std::string& command)
{
    if (g.percent <= 0)
        return g;
    g.width = int(std::lround(full.width() * g.percent / 100.0));
    g.height = int(std::lround(full.height() * g.percent / 100.0));
    if (g.width <= 0 || g.height <= 0)
        no_pixels(text, command);
    return g;
}

// oiiotool's rule, measured against oiiotool 2.4: GEOM is the new display window (its
// origin kept unless given), and the data window scales with it, its corner rounded
// down and its size up. Float arithmetic, as oiiotool's.
OIIO::ImageSpec resized_spec(const OIIO::ImageSpec& old, const Geometry& g)
{
    OIIO::ImageSpec spec = old;
    spec.full_width = g.width;
    spec.full_height = g.height;
    if (g.has_origin) {
        spec.full_x = g.x;
        spec.full_y = g.y;
    }
    // A file always has a display window; an image made without one uses its data window.
    const float sx = float(g.width) / float(old.full_width > 0 ? old.full_width : old.width);
    const float sy = float(g.height) / float(old.full_height > 0 ? old.full_height : old.height);
    spec.x = spec.full_x + int(std::floor(float(old.x - old.full_x) * sx));
    spec.y = spec.full_y + int(std::floor(float(old.y - old.full_y) * sy));
    spec.width = int(std::ceil(float(old.width) * sx));
    spec.height = int(std::ceil(float(old.height) * sy));
    return spec;
}

}  // namespace

Command crop_command()
{
    Command c;
    c.name = "--crop";
    c.arg_names = {"GEOM"};
    c.summary = "Set the pixel data window (WxH+X+Y or xmin,ymin,xmax,ymax), cropping or "
                "padding with zeros; the display window is kept";
    c.modifiers = {subimages_modifier()};
    c.check = [](const Invocation& inv) { parse_geometry(inv.args[0], false, inv.name); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const Geometry g = parse_geometry(inv.args[0], false, inv.name);
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            const OIIO::ImageSpec& spec = in[0]->spec();
            const int x = g.has_origin ? g.x : spec.x, y = g.has_origin ? g.y : spec.y;
            const OIIO::ROI roi(x, x + g.width, y, y + g.height, spec.z, spec.z + spec.depth, 0,
                                spec.nchannels);
            return OIIO::ImageBufAlgo::crop(*in[0], roi, ctx.nthreads);
        });
    };
    return c;
}

Command resize_command()
{
    Command c;
    c.name = "--resize";
    c.arg_names = {"GEOM"};
    c.summary = "Resample to a new display window size (WxH, WxH+X+Y or N%) with a filter; "
                "the data window scales with it";
    c.modifiers = {statmc::string_parameter("filter", "",
                                            "OIIO filter name (default: "
                                            "lanczos3 to shrink, blackman-harris "
                                            "to enlarge)")};
    c.modifiers.push_back(subimages_modifier());
    c.check = [](const Invocation& inv) { parse_geometry(inv.args[0], true, inv.name); };
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const std::string filter = inv.modifiers.values().get_string("filter");
        const Geometry geometry = parse_geometry(inv.args[0], true, inv.name);
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            const OIIO::ImageSpec& old = in[0]->spec();
            const Geometry g = sized_for(geometry, OIIO::get_roi_full(old), inv.args[0], inv.name);
            OIIO::ImageBuf resized(resized_spec(old, g));
            OIIO::ImageBufAlgo::resize(resized, *in[0], filter, 0.0f, resized.roi(), ctx.nthreads);
            return resized;
        });
    };
    return c;
}

}  // namespace statmc::tool
