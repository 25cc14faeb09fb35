#include "statmc/display/display.h"

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagebufalgo_util.h>

#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/renderer_presets.h"

namespace statmc {

namespace {

namespace OCIO = OCIO_NAMESPACE;

std::string config_path(const DisplayOptions& options)
{
    if (!options.config.empty())
        return options.config;
    const char* env = std::getenv("OCIO");
    if (env && *env)
        return env;
    throw std::invalid_argument("no OCIO config: give one or set $OCIO");
}

OCIO::ConstConfigRcPtr load_config(const std::string& path)
{
    try {
        return OCIO::Config::CreateFromFile(path.c_str());
    } catch (const OCIO::Exception& e) {
        throw std::invalid_argument("OCIO config " + path + ": " + e.what());
    }
}

std::string displays_of(const OCIO::ConstConfigRcPtr& cfg)
{
    std::string list;
    for (int i = 0; i < cfg->getNumDisplays(); ++i)
        list += (list.empty() ? "" : ", ") + std::string(cfg->getDisplay(i));
    return list;
}

std::string views_of(const OCIO::ConstConfigRcPtr& cfg, const std::string& display)
{
    std::string list;
    for (int i = 0; i < cfg->getNumViews(display.c_str()); ++i)
        list += (list.empty() ? "" : ", ") + std::string(cfg->getView(display.c_str(), i));
    return list;
}

bool listed(const std::string& list, const std::string& name)
{
    const std::string padded = ", " + list + ",";
    return padded.find(", " + name + ",") != std::string::npos;
}

// The display and view asked for (or the defaults), checked against the config so that
// a typo is named rather than reported as OCIO's generic failure.
std::pair<std::string, std::string> display_view(const OCIO::ConstConfigRcPtr& cfg,
                                                 const DisplayOptions& options,
                                                 const std::string& path)
{
    const std::string display =
        options.display.empty() ? cfg->getDefaultDisplay() : options.display;
    if (!listed(displays_of(cfg), display))
        throw std::invalid_argument("display '" + display + "' is not in OCIO config " + path +
                                    " (displays: " + displays_of(cfg) + ")");
    const std::string view =
        options.view.empty() ? cfg->getDefaultView(display.c_str()) : options.view;
    if (!listed(views_of(cfg, display), view))
        throw std::invalid_argument("view '" + view + "' of display '" + display +
                                    "' is not in OCIO config " + path +
                                    " (views: " + views_of(cfg, display) + ")");
    return {display, view};
}

// R,G,B (and A when present) of `given` as a float image, in that order: its own, or
// those a renderer's preset names.
OIIO::ImageBuf rgba_of(const OIIO::ImageBuf& given, int nthreads)
{
    layers::ImportedImage scratch;
    const OIIO::ImageBuf& src = layers::contract_beauty(given, scratch);
    std::vector<int> order;
    for (const char* name : {"R", "G", "B"}) {
        order.push_back(src.spec().channelindex(name));
        if (order.back() < 0)
            throw std::invalid_argument(std::string("the image has no channel ") + name);
    }
    if (const int a = src.spec().channelindex("A"); a >= 0)
        order.push_back(a);
    OIIO::ImageBuf rgba;
    if (!OIIO::ImageBufAlgo::channels(rgba, src, int(order.size()), order, {}, {}, false, nthreads))
        throw std::invalid_argument(rgba.geterror());
    if (rgba.spec().format != OIIO::TypeFloat)
        rgba = rgba.copy(OIIO::TypeFloat);
    return rgba;
}

void apply_rows(OIIO::ImageBuf& rgba, const OCIO::ConstCPUProcessorRcPtr& cpu, int nthreads)
{
    const int nch = rgba.spec().nchannels;
    OIIO::ImageBufAlgo::parallel_image(rgba.roi(), OIIO::paropt(nthreads), [&](OIIO::ROI r) {
        for (int y = r.ybegin; y < r.yend; ++y) {
            auto* row = static_cast<float*>(rgba.pixeladdr(r.xbegin, y));
            // Alpha (the 4th channel) is skipped by the stride: only R,G,B change.
            OCIO::PackedImageDesc desc(row, r.width(), 1, 3, OCIO::BIT_DEPTH_F32, sizeof(float),
                                       nch * sizeof(float), OCIO::AutoStride);
            cpu->apply(desc);
        }
    });
}

OIIO::ImageBuf display_image(const OIIO::ImageBuf& src, const DisplayOptions& options, int nthreads)
{
    if (!src.initialized())
        throw std::invalid_argument("uninitialized input image");
    const std::string path = config_path(options);
    const OCIO::ConstConfigRcPtr cfg = load_config(path);
    const auto [display, view] = display_view(cfg, options, path);
    OCIO::ConstCPUProcessorRcPtr cpu;
    try {
        cpu = cfg->getProcessor(OCIO::ROLE_SCENE_LINEAR, display.c_str(), view.c_str(),
                                OCIO::TRANSFORM_DIR_FORWARD)
                  ->getDefaultCPUProcessor();
    } catch (const OCIO::Exception& e) {
        throw std::invalid_argument("display '" + display + "', view '" + view + "': " + e.what());
    }
    OIIO::ImageBuf rgba = rgba_of(src, nthreads);
    apply_rows(rgba, cpu, nthreads);
    rgba.specmod().attribute("oiio:ColorSpace", view);
    return rgba;
}

}  // namespace

std::string display_config(const std::string& given, const std::string& module)
{
    if (!given.empty())
        return given;
    if (const char* env = std::getenv("OCIO"); env && *env)
        return env;
    if (module.empty())
        return {};
    return (std::filesystem::path(module).parent_path() / "display" / "config.ocio").string();
}

bool display(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const DisplayOptions& options,
             int nthreads)
{
    return layers::errors_on(dst, "display", [&] {
        dst = display_image(src, options, nthreads);
        return true;
    });
}

OIIO::ImageBuf display(const OIIO::ImageBuf& src, const DisplayOptions& options, int nthreads)
{
    return layers::returned_image(
        "display", [&](OIIO::ImageBuf& dst) { return display(dst, src, options, nthreads); });
}

}  // namespace statmc
