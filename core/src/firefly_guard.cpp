#include "statmc/core/firefly_guard.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

bool all_zero(const EstimatorImage& est, int x, int y)
{
    for (int c = 0; c < est.channels - est.context_channels; ++c)
        if (est.value[est.index(c, x, y)] != 0)
            return false;
    return true;
}

// Row y's testable flags (EstimatorImage::testable) and levels: the largest over the
// guarded channels of the per-sample variance on a scale where shot-like noise hardly
// depends on brightness (the Box-Cox variance for full statistics; for the untransformed
// test its first-order stand-in s²/μ, the variance of 2√x by the delta method, so that
// both routes guard the same quantity), 0 where untestable. Channel plane by channel
// plane and branch-free, so that the compiler vectorises it: pixel by pixel this was a
// fifth of the filter's fixed cost.
template <TestDomain kDomain>
bool levels_of_row(const EstimatorImage& est, int y, float* level, std::uint8_t* testable)
{
    const int w = est.width;
    const float* n = est.count.data() + est.index(0, 0, y);
    est.testable_row(y, testable);
    std::fill(level, level + w, 0.f);
    for (int c = 0; c < est.channels - est.context_channels; ++c) {
        const float* mean = est.test_mean.data() + est.index(c, 0, y);
        const float* variance = est.test_variance.data() + est.index(c, 0, y);
        for (int x = 0; x < w; ++x) {
            const float per_sample = variance[x] * n[x];
            float l = per_sample;
            if constexpr (kDomain == TestDomain::Untransformed) {
                const float m = std::abs(mean[x]);
                const float ratio = per_sample / m;
                l = per_sample == 0 ? per_sample
                    : m > 0         ? ratio
                                    : std::numeric_limits<float>::max();
            }
            level[x] = std::max(level[x], l);
        }
    }
    std::uint8_t all = 1;
    for (int x = 0; x < w; ++x) {
        level[x] = testable[x] ? level[x] : 0.f;
        all &= testable[x];
    }
    return all;
}

}  // namespace

bool firefly_guard_applies(const EstimatorImage&, float ratio) { return ratio > 0; }

NoiseLevels noise_levels(const EstimatorImage& est, float ratio)
{
    const int w = est.width, h = est.height;
    NoiseLevels out{std::vector<float>(est.pixels()), std::vector<float>(est.pixels()),
                    std::vector<float>(est.pixels(), 0.f), std::vector<float>(est.pixels())};
    std::vector<std::uint8_t> testable(est.pixels());
    std::vector<std::uint8_t> row_testable(h);  // every pixel of the row is
    for_each_row(h, [&](int y) {
        float* level = out.level.data() + std::size_t(y) * w;
        std::uint8_t* flags = testable.data() + std::size_t(y) * w;
        row_testable[y] = est.domain == TestDomain::BoxCox
                              ? levels_of_row<TestDomain::BoxCox>(est, y, level, flags)
                              : levels_of_row<TestDomain::Untransformed>(est, y, level, flags);
    });
    if (!firefly_guard_applies(est, ratio)) {
        std::fill(out.limit.begin(), out.limit.end(), kAny);
        std::fill(out.mutual_limit.begin(), out.mutual_limit.end(), kAny);
        return out;
    }
    if (!est.support.empty())
        for_each_row(h, [&](int y) {
            const std::size_t row = std::size_t(y) * w;
            for (int x = 0; x < w; ++x)
                out.own[row + x] = est.support[row + x] >= kGlintSupport ? out.level[row + x] : 0.f;
        });
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
        float* mutual = out.mutual_limit.data() + std::size_t(y) * w;
        for (int x = 0; x < w; ++x)
            mutual[x] = limit[x] > 0 ? limit[x] : kAny;
    });
    return out;
}

}  // namespace statmc
