#include "subimage_loop.h"

#include <optional>
#include <string>

#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/number_parsing.h"
#include "statmc/plugin_host/text_split.h"
#include "tool_context.h"

namespace statmc::tool {

namespace {

// Whether each subimage of `first` gets the operation; an empty result means subimage 0
// alone, as oiiotool works without -a.
std::vector<bool> selected_subimages(const ToolContext& ctx, const Invocation& inv,
                                     const StackImage& first)
{
    const std::size_t n = first.subimages.size();
    if (inv.modifiers.has("subimages")) {
        std::vector<bool> selected(n, false);
        for (const std::string& item : host::split_text(inv.modifiers.get_string("subimages")))
            selected[find_subimage(first, item, inv.name)] = true;
        return selected;
    }
    if (ctx.all_subimages)
        return std::vector<bool>(n, true);
    return {};
}

}  // namespace

std::size_t find_subimage(const StackImage& image, const std::string& which,
                          const std::string& command)
{
    for (std::size_t s = 0; s < image.subimages.size(); ++s)
        if (image.subimages[s].spec().get_string_attribute("oiio:subimagename") == which)
            return s;
    // Digits only: from_chars would take "-0" as an index.
    const bool digits =
        !which.empty() && which.find_first_not_of("0123456789") == std::string::npos;
    if (const std::optional<int> s = digits ? host::try_parse_int(which) : std::nullopt)
        if (std::size_t(*s) < image.subimages.size())
            return std::size_t(*s);
    std::vector<std::string> names;
    for (const OIIO::ImageBuf& sub : image.subimages)
        names.push_back(sub.spec().get_string_attribute("oiio:subimagename", "(unnamed)"));
    throw host::HostError(command + ": " + image.label + " has no subimage '" + which +
                          "' (it has " + std::to_string(image.subimages.size()) + ": " +
                          OIIO::Strutil::join(names, ", ") + ")");
}

host::ModifierSpec subimages_modifier()
{
    return statmc::string_parameter("subimages", "",
                                    "only these subimages (indices or part names); the "
                                    "others pass through");
}

void apply_to_subimages(ToolContext& ctx, const Invocation& inv, std::size_t count,
                        const SubimageOp& op)
{
    std::vector<StackImage> inputs = ctx.stack.pop(count, inv.name);
    const std::vector<bool> selected = selected_subimages(ctx, inv, inputs[0]);
    const std::size_t n = selected.empty() ? 1 : selected.size();
    if (!selected.empty())
        for (const StackImage& in : inputs)
            if (in.subimages.size() != n)
                throw host::HostError(inv.name + ": " + inputs[0].label + " has " +
                                      std::to_string(n) + " subimages but " + in.label + " has " +
                                      std::to_string(in.subimages.size()));
    std::vector<OIIO::ImageBuf> results;
    // A subimage that passes through keeps its MIP levels; a computed one has one level.
    layers::MipLevels levels(n);
    inputs[0].mip_levels.resize(inputs[0].subimages.size());
    for (std::size_t s = 0; s < n; ++s) {
        if (!selected.empty() && !selected[s]) {
            // inputs is ours (popped) and subimage s is read no more: moved, not copied.
            results.push_back(std::move(inputs[0].subimages[s]));
            levels[s] = std::move(inputs[0].mip_levels[s]);
            continue;
        }
        std::vector<const OIIO::ImageBuf*> images;
        for (const StackImage& in : inputs)
            images.push_back(&in.subimages[s]);
        OIIO::ImageBuf result = op(images);
        if (result.has_error())
            throw host::HostError(inv.name + ": " + inputs[0].label + ": " + result.geterror());
        results.push_back(std::move(result));
    }
    StackImage result{std::move(results), inputs[0].label + " (" + inv.name + ")"};
    result.mip_levels = std::move(levels);
    ctx.stack.push(std::move(result));
}

}  // namespace statmc::tool
