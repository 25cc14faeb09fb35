// Statistics planes moved across the image: what a camera pan does to a frame, for the
// temporal tests of core and of the denoise operator. Header-only, core types only.
#pragma once

#include <algorithm>
#include <vector>

#include "statmc/core/statistics_image.h"

namespace statmc::test {

/// What enters the image from outside: pixels without samples (count 0), or copies of the
/// nearest edge pixel (every pixel stays valid, as the denoise operator's check requires).
enum class Entering { Empty, EdgeCopy };

/// Dense channel-major planes of width × height translated by (sx, sy): pixel (x, y) of the
/// result is (x − sx, y − sy) of the input.
inline std::vector<float> shifted_planes(const std::vector<float>& from, int width, int height,
                                         int sx, int sy, Entering entering)
{
    std::vector<float> to(from.size());
    const std::size_t n = std::size_t(width) * height;
    for (std::size_t c = 0; c < from.size() / n; ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                int u = x - sx, v = y - sy;
                const bool in = u >= 0 && v >= 0 && u < width && v < height;
                u = std::clamp(u, 0, width - 1);
                v = std::clamp(v, 0, height - 1);
                to[c * n + std::size_t(y) * width + x] =
                    in || entering == Entering::EdgeCopy ? from[c * n + std::size_t(v) * width + u]
                                                         : 0.f;
            }
    return to;
}

/// `p` translated by (sx, sy), every plane it has.
inline StatisticsPlanes shifted(const StatisticsPlanes& p, int sx, int sy, Entering entering)
{
    StatisticsPlanes out = p;
    for (auto member : {&StatisticsPlanes::count, &StatisticsPlanes::mean,
                        &StatisticsPlanes::variance, &StatisticsPlanes::bc_mean,
                        &StatisticsPlanes::bc_variance, &StatisticsPlanes::bc_moment3,
                        &StatisticsPlanes::moment3, &StatisticsPlanes::moment4,
                        &StatisticsPlanes::bc_moment4})
        out.*member = shifted_planes(p.*member, p.width, p.height, sx, sy, entering);
    return out;
}

}  // namespace statmc::test
