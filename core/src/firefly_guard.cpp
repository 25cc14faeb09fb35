#include "statmc/core/firefly_guard.h"

#include <algorithm>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace statmc {

namespace {

constexpr int kMinNeighbours = 3;  // a median of fewer says nothing about the neighbourhood
constexpr float kAny = std::numeric_limits<float>::infinity();

template <class Body>
void for_each_row(int height, Body&& body)
{
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            body(y);
    });
}

/// The upper median of k values (the k/2-th smallest), robust to a noisy pixel or two
/// next door. All eight neighbours, the common case, go through a sorting network.
float upper_median(float* v, int k)
{
    if (k != 8) {
        std::nth_element(v, v + k / 2, v + k);
        return v[k / 2];
    }
    auto order = [&](int a, int b) {
        const float lo = std::min(v[a], v[b]), hi = std::max(v[a], v[b]);
        v[a] = lo;
        v[b] = hi;
    };
    // Batcher's odd-even merge sort of eight values.
    order(0, 1); order(2, 3); order(4, 5); order(6, 7);
    order(0, 2); order(1, 3); order(4, 6); order(5, 7);
    order(1, 2); order(5, 6);
    order(0, 4); order(1, 5); order(2, 6); order(3, 7);
    order(2, 4); order(3, 5);
    order(1, 2); order(3, 4); order(5, 6);
    return v[4];
}

bool all_zero(const EstimatorImage& est, int x, int y)
{
    for (int c = 0; c < est.channels; ++c)
        if (est.value[est.index(c, x, y)] != 0)
            return false;
    return true;
}

}  // namespace

bool firefly_guard_applies(const EstimatorImage& est, float ratio)
{
    return ratio > 0 && est.domain == TestDomain::BoxCox;
}

NoiseLevels noise_levels(const EstimatorImage& est, float ratio)
{
    const int w = est.width, h = est.height;
    NoiseLevels out{std::vector<float>(est.pixels(), 0.f), std::vector<float>(est.pixels(), kAny)};
    std::vector<std::uint8_t> testable(est.pixels());
    for_each_row(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            testable[i] = est.testable(x, y);
            if (!testable[i])
                continue;
            float level = 0;
            for (int c = 0; c < est.channels; ++c)
                level = std::max(level, est.test_variance[est.index(c, x, y)] * est.count[i]);
            out.level[i] = level;
        }
    });
    if (!firefly_guard_applies(est, ratio))
        return out;
    for_each_row(h, [&](int y) {
        float around[8];
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            if (!testable[i])
                continue;
            int k = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if ((dx || dy) && u >= 0 && v >= 0 && u < w && v < h &&
                        testable[std::size_t(v) * w + u])
                        around[k++] = out.level[std::size_t(v) * w + u];
                }
            if (k < kMinNeighbours)
                continue;
            const float reference = std::max(out.level[i], upper_median(around, k));
            if (reference > 0)
                out.limit[i] = ratio * reference;
            else if (!all_zero(est, x, y))
                out.limit[i] = 0;  // noise-free and lit (an emitter): certain, takes only its equals
        }
    });
    return out;
}

}  // namespace statmc
