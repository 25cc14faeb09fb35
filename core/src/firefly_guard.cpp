#include "statmc/core/firefly_guard.h"

#include <algorithm>
#include <cmath>
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
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 16),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (int y = rows.begin(); y < rows.end(); ++y)
                              body(y);
                      });
}

/// The upper median (fifth smallest) of eight values by Batcher's odd-even merge sort:
/// branch-free, so a row of them vectorises.
inline float upper_median_of_eight(float* v)
{
    auto order = [&](int a, int b) {
        const float lo = std::min(v[a], v[b]), hi = std::max(v[a], v[b]);
        v[a] = lo;
        v[b] = hi;
    };
    order(0, 1);
    order(2, 3);
    order(4, 5);
    order(6, 7);
    order(0, 2);
    order(1, 3);
    order(4, 6);
    order(5, 7);
    order(1, 2);
    order(5, 6);
    order(0, 4);
    order(1, 5);
    order(2, 6);
    order(3, 7);
    order(2, 4);
    order(3, 5);
    order(1, 2);
    order(3, 4);
    order(5, 6);
    return v[4];
}

/// The upper median of k values (the k/2-th smallest), robust to a noisy pixel or two
/// next door.
float upper_median(float* v, int k)
{
    if (k == 8)
        return upper_median_of_eight(v);
    std::nth_element(v, v + k / 2, v + k);
    return v[k / 2];
}

/// Channel c's per-sample variance on a scale where shot-like noise hardly depends on
/// brightness: the Box-Cox variance for full statistics; for the untransformed test its
/// first-order stand-in s²/μ (the variance of 2√x by the delta method), so that both
/// routes guard the same quantity.
float channel_level(const EstimatorImage& est, int c, int x, int y)
{
    const std::size_t k = est.index(c, x, y);
    const float per_sample = est.test_variance[k] * est.count[est.index(0, x, y)];
    if (est.domain == TestDomain::BoxCox || per_sample == 0)
        return per_sample;
    const float mean = std::abs(est.test_mean[k]);
    return mean > 0 ? per_sample / mean : std::numeric_limits<float>::max();
}

bool all_zero(const EstimatorImage& est, int x, int y)
{
    for (int c = 0; c < est.channels - est.context_channels; ++c)
        if (est.value[est.index(c, x, y)] != 0)
            return false;
    return true;
}

}  // namespace

bool firefly_guard_applies(const EstimatorImage&, float ratio) { return ratio > 0; }

NoiseLevels noise_levels(const EstimatorImage& est, float ratio)
{
    const int w = est.width, h = est.height;
    NoiseLevels out{std::vector<float>(est.pixels()), std::vector<float>(est.pixels())};
    std::vector<std::uint8_t> testable(est.pixels());
    std::vector<std::uint8_t> row_testable(h);  // every pixel of the row is
    for_each_row(h, [&](int y) {
        bool all = true;
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            testable[i] = est.testable(x, y);
            all = all && testable[i];
            float level = 0;
            if (testable[i])
                for (int c = 0; c < est.channels - est.context_channels; ++c)
                    level = std::max(level, channel_level(est, c, x, y));
            out.level[i] = level;
        }
        row_testable[y] = all;
    });
    if (!firefly_guard_applies(est, ratio)) {
        std::fill(out.limit.begin(), out.limit.end(), kAny);
        return out;
    }
    auto level = [&](int x, int y) { return out.level[std::size_t(y) * w + x]; };
    for_each_row(h, [&](int y) {
        float* limit = out.limit.data() + std::size_t(y) * w;
        // Inside rows whose 3×3 neighbourhoods are all testable — nearly every row — the
        // eight neighbours' medians go through the sorting network a whole row at a time,
        // which the compiler vectorises.
        std::vector<float> median(w, -1.f);  // −1: not computed
        if (y > 0 && y + 1 < h && row_testable[y - 1] && row_testable[y] && row_testable[y + 1])
            for (int x = 1; x + 1 < w; ++x) {
                float around[8] = {level(x - 1, y - 1), level(x, y - 1),    level(x + 1, y - 1),
                                   level(x - 1, y),     level(x + 1, y),    level(x - 1, y + 1),
                                   level(x, y + 1),     level(x + 1, y + 1)};
                median[x] = upper_median_of_eight(around);
            }
        for (int x = 0; x < w; ++x) {
            limit[x] = kAny;
            if (!testable[std::size_t(y) * w + x])
                continue;
            float m = median[x];
            if (m < 0) {  // a border, or an untestable pixel nearby
                float around[8];
                int k = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int u = x + dx, v = y + dy;
                        if ((dx || dy) && u >= 0 && v >= 0 && u < w && v < h &&
                            testable[std::size_t(v) * w + u])
                            around[k++] = level(u, v);
                    }
                if (k < kMinNeighbours)
                    continue;
                m = upper_median(around, k);
            }
            const float reference = std::max(level(x, y), m);
            if (reference > 0)
                limit[x] = ratio * reference;
            else if (!all_zero(est, x, y))
                limit[x] = 0;  // noise-free and lit (an emitter): certain, takes only its equals
        }
    });
    return out;
}

}  // namespace statmc
