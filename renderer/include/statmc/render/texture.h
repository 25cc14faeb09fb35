// pbrt's "imagemap" texture: an RGB image looked up bilinearly with repeat wrapping.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "statmc/render/vec.h"

namespace statmc::render {

class ImageTexture {
public:
    /// Reads `path` through OIIO. 8-bit formats (TGA, PNG, JPEG...) are sRGB-encoded and
    /// decoded to linear when `gamma` says so, as pbrt-v3 does by default for .tga/.png.
    /// Throws std::runtime_error naming the file when it cannot be read.
    static std::shared_ptr<const ImageTexture> load(const std::string& path, bool gamma,
                                                    float scale);
    /// A texture from pixels (rows top to bottom, RGB interleaved), for tests.
    ImageTexture(int width, int height, std::vector<float> rgb);

    /// The colour at texture coordinates (u, v). pbrt-v3 flips images on load so that
    /// v = 0 is the bottom row; that is done here by looking up row (1 − v).
    Rgb lookup(float u, float v) const;
    /// The average colour, used where a single colour stands for the texture.
    Rgb average() const;

private:
    int width_;
    int height_;
    std::vector<float> rgb_;
    Rgb texel(int x, int y) const;
};

/// pbrt's default for an imagemap's "gamma": true for 8-bit formats (.tga, .png).
bool default_texture_gamma(const std::string& path);

}  // namespace statmc::render
