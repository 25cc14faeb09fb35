#include "statmc/compare/compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/compare/ssim.h"
#include "statmc/core/luminance.h"
#include "statmc/layers/frame_match.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/renderer_presets.h"

namespace statmc {

namespace {

// The R,G,B channels of `given` as a float image, found by name (OIIO may reorder them),
// or those a renderer's preset names (a Cycles reference's ViewLayer.Combined).
OIIO::ImageBuf beauty(const OIIO::ImageBuf& given, const char* role, int nthreads)
{
    layers::ImportedImage scratch;
    const OIIO::ImageBuf& buf = layers::contract_beauty(given, scratch);
    const OIIO::ImageSpec& spec = buf.spec();
    std::array<int, 3> order{};
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        if ((order[c] = spec.channelindex(names[c])) < 0)
            throw std::invalid_argument(std::string(role) +
                                        (given.name().empty() ? "" : " " + std::string(given.name())) +
                                        " has no channel " + names[c]);
    OIIO::ImageBuf rgb;
    if (!OIIO::ImageBufAlgo::channels(rgb, buf, 3, order, {}, {}, false, nthreads))
        throw std::invalid_argument(rgb.geterror());
    return rgb;
}

float clamped(float v) { return std::clamp(std::isfinite(v) ? v : 0.f, 0.f, 1.f); }

// sRGB's encoding (IEC 61966-2-1), then clamped: the LDR image SSIM is defined on.
float display_value(float linear)
{
    const float v =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
    return clamped(v);
}

// The luminance of the LDR pixels of `rgb` (3 channels).
std::vector<float> ldr_luminance(const std::vector<float>& rgb, bool encode)
{
    std::vector<float> y(rgb.size() / 3);
    for (std::size_t p = 0; p < y.size(); ++p) {
        float v[3];
        for (int c = 0; c < 3; ++c)
            v[c] = encode ? display_value(rgb[3 * p + c]) : clamped(rgb[3 * p + c]);
        y[p] = luminance(v[0], v[1], v[2]);
    }
    return y;
}

std::vector<float> pixels_of(const OIIO::ImageBuf& buf)
{
    std::vector<float> p(std::size_t(buf.spec().width) * buf.spec().height * 3);
    buf.get_pixels(buf.roi(), OIIO::TypeFloat, p.data());
    return p;
}

// The luminance SSIM compares: through the display transform when one is given.
std::vector<float> ldr_of(const OIIO::ImageBuf& rgb, const CompareOptions& options, int nthreads)
{
    if (!options.display)
        return ldr_luminance(pixels_of(rgb), true);
    OIIO::ImageBuf shown;
    if (!statmc::display(shown, rgb, *options.display, nthreads))
        throw std::invalid_argument(shown.geterror());
    return ldr_luminance(pixels_of(shown), false);
}

CompareMetrics metrics_of(const OIIO::ImageBuf& x, const OIIO::ImageBuf& ref,
                          const CompareOptions& options, int nthreads)
{
    const OIIO::ImageSpec& spec = x.spec();
    const int w = spec.width, h = spec.height;
    const std::vector<float> px = pixels_of(x), pr = pixels_of(ref);
    const double epsilon = options.relmse_epsilon;
    double se = 0, ae = 0, rel = 0;
    for (std::size_t i = 0; i < px.size(); ++i) {
        const double d = double(px[i]) - pr[i];
        se += d * d;
        ae += std::abs(d);
        rel += d * d / (double(pr[i]) * pr[i] + epsilon);
    }
    CompareMetrics m;
    const double n = double(px.size());
    m.rmse = std::sqrt(se / n);
    m.mae = ae / n;
    m.relmse = rel / n;
    m.ssim = mean_ssim(ldr_of(x, options, nthreads), ldr_of(ref, options, nthreads), w, h);
    m.dssim = (1 - m.ssim) / 2;
    return m;
}

}  // namespace

bool compare(CompareMetrics& metrics, OIIO::ImageBuf& error, const OIIO::ImageBuf& image,
             const OIIO::ImageBuf& reference, const CompareOptions& options, int nthreads)
{
    return layers::errors_on(error, "compare", [&] {
        if (!image.initialized() || !reference.initialized())
            throw std::invalid_argument("compare: uninitialized input image");
        if (!(options.relmse_epsilon > 0))
            throw std::invalid_argument("compare: epsilon must be > 0");
        layers::require_same_frame(image.spec(), reference.spec(), "the image and the reference");
        const OIIO::ImageBuf x = beauty(image, "the image", nthreads);
        const OIIO::ImageBuf ref = beauty(reference, "the reference", nthreads);
        metrics = metrics_of(x, ref, options, nthreads);
        if (!OIIO::ImageBufAlgo::absdiff(error, x, ref, {}, nthreads))
            throw std::invalid_argument(error.geterror());
        return true;
    });
}

}  // namespace statmc
