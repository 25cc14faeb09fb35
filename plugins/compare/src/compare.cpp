#include "statmc/compare/compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/compare/ssim.h"

namespace statmc {

namespace {

// The R,G,B channels of `buf` as a float image, found by name (OIIO may reorder them).
OIIO::ImageBuf beauty(const OIIO::ImageBuf& buf, const char* role, int nthreads)
{
    const OIIO::ImageSpec& spec = buf.spec();
    std::array<int, 3> order{};
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        if ((order[c] = spec.channelindex(names[c])) < 0)
            throw std::invalid_argument(std::string(role) +
                                        (buf.name().empty() ? "" : " " + std::string(buf.name())) +
                                        " has no channel " + names[c]);
    OIIO::ImageBuf rgb;
    if (!OIIO::ImageBufAlgo::channels(rgb, buf, 3, order, {}, {}, false, nthreads))
        throw std::invalid_argument(rgb.geterror());
    return rgb;
}

void check_match(const OIIO::ImageSpec& a, const OIIO::ImageSpec& b)
{
    if (a.width != b.width || a.height != b.height || a.x != b.x || a.y != b.y)
        throw std::invalid_argument(OIIO::Strutil::fmt::format(
            "the image ({}x{} at {},{}) and the reference ({}x{} at {},{}) differ in data "
            "window",
            a.width, a.height, a.x, a.y, b.width, b.height, b.x, b.y));
}

// sRGB's encoding (IEC 61966-2-1), then clamped: the LDR image SSIM is defined on.
float display_value(float linear)
{
    const float v = linear <= 0.0031308f ? 12.92f * linear
                                         : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
    return std::clamp(std::isfinite(v) ? v : 0.f, 0.f, 1.f);
}

float luminance(const float* rgb)
{
    return 0.2126f * display_value(rgb[0]) + 0.7152f * display_value(rgb[1]) +
           0.0722f * display_value(rgb[2]);
}

CompareMetrics metrics_of(const OIIO::ImageBuf& x, const OIIO::ImageBuf& ref, double epsilon)
{
    const OIIO::ImageSpec& spec = x.spec();
    const int w = spec.width, h = spec.height;
    std::vector<float> px(std::size_t(w) * h * 3), pr(px.size());
    x.get_pixels(x.roi(), OIIO::TypeFloat, px.data());
    ref.get_pixels(ref.roi(), OIIO::TypeFloat, pr.data());
    double se = 0, ae = 0, rel = 0;
    std::vector<float> lx(std::size_t(w) * h), lr(lx.size());
    for (std::size_t i = 0; i < px.size(); ++i) {
        const double d = double(px[i]) - pr[i];
        se += d * d;
        ae += std::abs(d);
        rel += d * d / (double(pr[i]) * pr[i] + epsilon);
    }
    for (std::size_t p = 0; p < lx.size(); ++p) {
        lx[p] = luminance(&px[3 * p]);
        lr[p] = luminance(&pr[3 * p]);
    }
    CompareMetrics m;
    const double n = double(px.size());
    m.rmse = std::sqrt(se / n);
    m.mae = ae / n;
    m.relmse = rel / n;
    m.ssim = mean_ssim(lx, lr, w, h);
    m.dssim = (1 - m.ssim) / 2;
    return m;
}

}  // namespace

bool compare(CompareMetrics& metrics, OIIO::ImageBuf& error, const OIIO::ImageBuf& image,
             const OIIO::ImageBuf& reference, const CompareOptions& options, int nthreads)
{
    try {
        if (!image.initialized() || !reference.initialized())
            throw std::invalid_argument("compare: uninitialized input image");
        if (!(options.relmse_epsilon > 0))
            throw std::invalid_argument("compare: epsilon must be > 0");
        check_match(image.spec(), reference.spec());
        const OIIO::ImageBuf x = beauty(image, "the image", nthreads);
        const OIIO::ImageBuf ref = beauty(reference, "the reference", nthreads);
        metrics = metrics_of(x, ref, options.relmse_epsilon);
        if (!OIIO::ImageBufAlgo::absdiff(error, x, ref, {}, nthreads))
            throw std::invalid_argument(error.geterror());
        return true;
    } catch (const std::exception& e) {
        error.errorfmt("{}", e.what());
    }
    return false;
}

}  // namespace statmc
