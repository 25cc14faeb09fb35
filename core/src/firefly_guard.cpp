#include "statmc/core/firefly_guard.h"

#include <algorithm>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace statmc {

namespace {

constexpr int kMinNeighbours = 3;  // a median of fewer says nothing about the neighbourhood

float sample_variance(const EstimatorImage& est, int c, int x, int y)
{
    return est.test_variance[est.index(c, x, y)] * est.count[est.index(0, x, y)];
}

bool is_firefly(const EstimatorImage& est, float ratio, int x, int y)
{
    if (!est.testable(x, y))
        return false;
    float around[8];
    for (int c = 0; c < est.channels; ++c) {
        int k = 0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int u = x + dx, v = y + dy;
                if ((dx || dy) && u >= 0 && v >= 0 && u < est.width && v < est.height && est.testable(u, v))
                    around[k++] = sample_variance(est, c, u, v);
            }
        if (k < kMinNeighbours)
            return false;
        // The upper median, robust to another firefly next door.
        std::nth_element(around, around + k / 2, around + k);
        const float median = around[k / 2];
        if (median > 0 && sample_variance(est, c, x, y) > ratio * median)
            return true;
    }
    return false;
}

}  // namespace

std::vector<std::uint8_t> find_fireflies(const EstimatorImage& est, float ratio)
{
    std::vector<std::uint8_t> flags(est.pixels(), 0);
    if (!(ratio > 0))
        return flags;
    // The median of the neighbours is at least their minimum, so a pixel within `ratio`
    // of its smallest testable neighbour in every channel is no firefly. That test is a
    // streaming minimum over padded planes (untestable and outside = +∞); only the rare
    // pixels it cannot clear take the median.
    const int w = est.width, h = est.height, pw = w + 2;
    constexpr float kAbsent = std::numeric_limits<float>::infinity();
    std::vector<float> padded(std::size_t(pw) * (h + 2) * est.channels, kAbsent);
    auto padded_at = [&](int c, int x, int y) -> float& {
        return padded[(std::size_t(c) * (h + 2) + (y + 1)) * pw + (x + 1)];
    };
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < w; ++x)
                if (est.testable(x, y))
                    for (int c = 0; c < est.channels; ++c)
                        padded_at(c, x, y) = sample_variance(est, c, x, y);
    });

    tbb::parallel_for(tbb::blocked_range<int>(0, h, 16), [&](const tbb::blocked_range<int>& rows) {
        std::vector<std::uint8_t> suspect(w);
        for (int y = rows.begin(); y < rows.end(); ++y) {
            std::fill(suspect.begin(), suspect.end(), 0);
            for (int c = 0; c < est.channels; ++c) {
                const float* up = &padded_at(c, -1, y - 1);
                const float* mid = &padded_at(c, -1, y);
                const float* down = &padded_at(c, -1, y + 1);
                for (int x = 0; x < w; ++x) {
                    const float lowest = std::min({up[x], up[x + 1], up[x + 2], mid[x], mid[x + 2],
                                                   down[x], down[x + 1], down[x + 2]});
                    // A +∞ centre (untestable) compares false and is never suspect.
                    suspect[x] |= mid[x + 1] > ratio * lowest && mid[x + 1] != kAbsent;
                }
            }
            for (int x = 0; x < w; ++x)
                if (suspect[x])
                    flags[std::size_t(y) * w + x] = is_firefly(est, ratio, x, y);
        }
    });
    return flags;
}

}  // namespace statmc
