#include "statmc/render/texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"

namespace statmc::render {

namespace {

float srgb_to_linear(float v)
{
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

std::string lower_extension(const std::string& path)
{
    const auto dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

bool default_texture_gamma(const std::string& path)
{
    const std::string ext = lower_extension(path);
    return ext == "tga" || ext == "png";
}

ImageTexture::ImageTexture(int width, int height, std::vector<float> rgb)
    : width_(width), height_(height), rgb_(std::move(rgb))
{
    if (width <= 0 || height <= 0 || rgb_.size() != std::size_t(width) * height * 3)
        throw std::invalid_argument("ImageTexture: pixel count does not match resolution");
}

std::shared_ptr<const ImageTexture> ImageTexture::load(const std::string& path, bool gamma,
                                                       float scale)
{
    // The input checks of every statmc read first (a damaged EXR, a hostile header).
    try {
        layers::check_image_file(path);
    } catch (const layers::FileError& e) {
        throw std::runtime_error(std::string("cannot read texture: ") + e.what());
    }
    OIIO::ImageBuf buf(path);
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error("cannot read texture '" + path + "': " + buf.geterror());
    const OIIO::ImageSpec& spec = buf.spec();
    const int w = spec.width, h = spec.height, nc = spec.nchannels;
    std::vector<float> pixels(std::size_t(w) * h * nc);
    buf.get_pixels(OIIO::ROI(spec.x, spec.x + w, spec.y, spec.y + h, 0, 1, 0, nc),
                   OIIO::TypeDesc::FLOAT, pixels.data());
    // 8-bit files (the common case for sRGB textures) decode through a 256-entry table:
    // a pow per texel made loading Veach Ajar's textures slower than building its BVH.
    const bool eight_bit = buf.nativespec().format == OIIO::TypeDesc::UINT8;
    float table[256];
    for (int i = 0; i < 256; ++i)
        table[i] = srgb_to_linear(float(i) / 255.f);
    std::vector<float> rgb(std::size_t(w) * h * 3);
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i)
        for (int c = 0; c < 3; ++c) {
            float v = pixels[i * nc + std::min(c, nc - 1)];
            if (gamma) {
                const float q = v * 255.f;
                const float r = std::round(q);
                v = eight_bit && r >= 0 && r <= 255 && std::abs(q - r) < 1e-3f ? table[int(r)]
                                                                               : srgb_to_linear(v);
            }
            rgb[i * 3 + c] = v * scale;
        }
    return std::make_shared<const ImageTexture>(w, h, std::move(rgb));
}

Rgb ImageTexture::texel(int x, int y) const
{
    x = ((x % width_) + width_) % width_;
    y = ((y % height_) + height_) % height_;
    const float* p = &rgb_[(std::size_t(y) * width_ + x) * 3];
    return {p[0], p[1], p[2]};
}

Rgb ImageTexture::lookup(float u, float v) const
{
    if (!std::isfinite(u) || !std::isfinite(v))
        return texel(0, 0);
    // Repeat wrapping first, so that far-away coordinates never overflow an int.
    u -= std::floor(u);
    v -= std::floor(v);
    const float x = u * width_ - 0.5f;
    const float y = (1.f - v) * height_ - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const int x0 = int(fx), y0 = int(fy);
    const float dx = x - fx, dy = y - fy;
    return texel(x0, y0) * ((1 - dx) * (1 - dy)) + texel(x0 + 1, y0) * (dx * (1 - dy)) +
           texel(x0, y0 + 1) * ((1 - dx) * dy) + texel(x0 + 1, y0 + 1) * (dx * dy);
}

Rgb ImageTexture::average() const
{
    double s[3] = {0, 0, 0};
    for (std::size_t i = 0; i < rgb_.size(); ++i)
        s[i % 3] += rgb_[i];
    const double n = double(width_) * height_;
    return {float(s[0] / n), float(s[1] / n), float(s[2] / n)};
}

}  // namespace statmc::render
