#include "statmc/oidn/oidn.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "oidn_library.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/renderer_presets.h"

namespace statmc {

namespace {

std::string image_label(const OIIO::ImageBuf& image)
{
    return image.name().empty() ? std::string("the image")
                                : std::string("the image (") + std::string(image.name()) + ")";
}

// Channels `indices` of `in` packed as OIDN's FLOAT3 pixels.
std::vector<float> packed(const OIIO::ImageBuf& in, const std::vector<int>& indices)
{
    const OIIO::ImageSpec& s = in.spec();
    std::vector<float> out(std::size_t(s.width) * s.height * 3);
    for (int c = 0; c < 3; ++c) {
        const ConstPlane plane = layers::channel_plane(in, indices[c]);
        for (int y = 0; y < s.height; ++y)
            for (int x = 0; x < s.width; ++x)
                out[(std::size_t(y) * s.width + x) * 3 + c] = plane(x, y);
    }
    return out;
}

void require_finite(const std::vector<float>& colour, const OIIO::ImageBuf& image)
{
    const OIIO::ImageSpec& s = image.spec();
    for (std::size_t i = 0; i < colour.size(); ++i)
        if (!std::isfinite(colour[i])) {
            const std::size_t pixel = i / 3;
            throw std::invalid_argument("oidn: " + image_label(image) +
                                        " holds NaN or Inf in its beauty at pixel (" +
                                        std::to_string(s.x + int(pixel % s.width)) + ", " +
                                        std::to_string(s.y + int(pixel / s.width)) + ")");
        }
}

// A device and its filter, released however the call ends.
struct Session {
    const oidn_api::Functions& api;
    oidn_api::Device device = nullptr;
    oidn_api::Filter filter = nullptr;
    ~Session()
    {
        if (filter)
            api.release_filter(filter);
        if (device)
            api.release_device(device);
    }
    void check(const char* stage) const
    {
        const char* message = nullptr;
        if (api.get_device_error(device, &message) != oidn_api::kErrorNone)
            throw std::runtime_error(std::string("oidn: ") + stage +
                                     " failed: " + (message ? message : "no message"));
    }
};

bool oidn_impl(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const OidnOptions& opt, int nthreads)
{
    const oidn_api::Functions& api = oidn_api::load(opt.library);
    layers::ImportedImage imported;
    OIIO::ImageBuf floats;
    const OIIO::ImageBuf& in =
        layers::local_float_pixels(layers::contract_beauty(src, imported), floats);
    const OIIO::ImageSpec& spec = in.spec();
    std::vector<int> beauty;
    for (const char* c : {"R", "G", "B"})
        beauty.push_back(spec.channelindex(c));
    std::vector<float> colour = packed(in, beauty);
    require_finite(colour, src);
    std::vector<float> albedo, normal;
    if (opt.guides) {
        if (const auto a = layers::find_guide_layer(spec, layers::kAlbedoLayer, true); !a.empty())
            albedo = packed(in, a);
        // OIDN takes a normal only beside an albedo.
        if (const auto n = layers::find_guide_layer(spec, layers::kNormalLayer, false);
            !n.empty() && !albedo.empty())
            normal = packed(in, n);
    }
    std::vector<float> output(colour.size());

    Session session{api};
    session.device = api.new_device(oidn_api::kDeviceTypeCpu);
    if (!session.device)
        throw std::runtime_error("oidn: no CPU device (this CPU may lack SSE4.1)");
    if (nthreads > 0)
        api.set_device_int(session.device, "numThreads", nthreads);
    api.commit_device(session.device);
    session.check("creating the CPU device");
    session.filter = api.new_filter(session.device, "RT");
    const std::size_t w = spec.width, h = spec.height;
    auto image = [&](const char* name, std::vector<float>& data) {
        if (!data.empty())
            api.set_shared_filter_image(session.filter, name, data.data(), oidn_api::kFormatFloat3,
                                        w, h, 0, 0, 0);
    };
    image("color", colour);
    image("albedo", albedo);
    image("normal", normal);
    image("output", output);
    api.set_filter_bool(session.filter, "hdr", true);
    api.commit_filter(session.filter);
    session.check("setting up the filter");
    api.execute_filter(session.filter);
    session.check("denoising");

    dst.copy(in, OIIO::TypeFloat);
    for (int c = 0; c < 3; ++c) {
        const Plane plane = layers::channel_plane(dst, beauty[c]);
        for (int y = 0; y < spec.height; ++y)
            for (int x = 0; x < spec.width; ++x)
                plane(x, y) = output[(std::size_t(y) * w + x) * 3 + c];
    }
    dst.specmod().attribute(layers::attr::kDenoised, 1);
    return true;
}

}  // namespace

bool oidn_denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const OidnOptions& opt,
                  int nthreads)
{
    return layers::errors_on(dst, "oidn", [&] { return oidn_impl(dst, src, opt, nthreads); });
}

OIIO::ImageBuf oidn_denoise(const OIIO::ImageBuf& src, const OidnOptions& opt, int nthreads)
{
    return layers::returned_image(
        "oidn", [&](OIIO::ImageBuf& dst) { return oidn_denoise(dst, src, opt, nthreads); });
}

std::string oidn_library_search_text() { return oidn_api::search_text(); }

}  // namespace statmc
