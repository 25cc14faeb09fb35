// --crop and --resize: the pixel data window, through ImageBufAlgo.
#include <cmath>
#include <cstdio>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/tool/command_table.h"
#include "statmc/tool/subimage_loop.h"
#include "statmc/tool/tool_context.h"
#include "statmc/tool/tool_error.h"

namespace statmc::tool {

namespace {

struct Geometry {
    int width = 0, height = 0;
    bool has_origin = false;
    int x = 0, y = 0;
};

// oiiotool's GEOM: "WxH", "WxH+X+Y" (signed offsets) or "xmin,ymin,xmax,ymax"
// (inclusive); with `percent_of`, "N%" scales that window's size (rounded).
Geometry parse_geometry(const std::string& text, const OIIO::ROI* percent_of,
                        const std::string& command)
{
    Geometry g;
    char tail = 0;
    int xmin, ymin, xmax, ymax;
    double percent = 0;
    if (std::sscanf(text.c_str(), "%d,%d,%d,%d%c", &xmin, &ymin, &xmax, &ymax, &tail) == 4 &&
        xmax >= xmin && ymax >= ymin) {
        g = {xmax - xmin + 1, ymax - ymin + 1, true, xmin, ymin};
    } else if (std::sscanf(text.c_str(), "%dx%d%d%d%c", &g.width, &g.height, &g.x, &g.y,
                           &tail) == 4 &&
               text.find_first_of("+-", text.find('x')) != std::string::npos) {
        g.has_origin = true;
    } else if (std::sscanf(text.c_str(), "%dx%d%c", &g.width, &g.height, &tail) == 2) {
    } else if (percent_of && std::sscanf(text.c_str(), "%lf%%%c", &percent, &tail) == 1 &&
               percent > 0) {
        g.width = int(std::lround(percent_of->width() * percent / 100.0));
        g.height = int(std::lround(percent_of->height() * percent / 100.0));
    } else {
        throw ToolError(command + ": geometry '" + text + "' is not WxH, WxH+X+Y" +
                        (percent_of ? ", N%" : "") + " or xmin,ymin,xmax,ymax");
    }
    if (g.width <= 0 || g.height <= 0)
        throw ToolError(command + ": geometry '" + text + "' has no pixels");
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
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            const OIIO::ImageSpec& spec = in[0]->spec();
            const Geometry g = parse_geometry(inv.args[0], nullptr, inv.name);
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
    c.modifiers = {statmc::string_parameter("filter", "", "OIIO filter name (default: "
                                                          "lanczos3 to shrink, blackman-harris "
                                                          "to enlarge)")};
    c.modifiers.push_back(subimages_modifier());
    c.run = [](ToolContext& ctx, const Invocation& inv) {
        const std::string filter = inv.modifiers.values().get_string("filter");
        apply_to_subimages(ctx, inv, 1, [&](const auto& in) {
            const OIIO::ImageSpec& old = in[0]->spec();
            const OIIO::ROI full = OIIO::get_roi_full(old);
            const Geometry g = parse_geometry(inv.args[0], &full, inv.name);
            OIIO::ImageBuf resized(resized_spec(old, g));
            OIIO::ImageBufAlgo::resize(resized, *in[0], filter, 0.0f, resized.roi(),
                                       ctx.nthreads);
            return resized;
        });
    };
    return c;
}

}  // namespace statmc::tool
