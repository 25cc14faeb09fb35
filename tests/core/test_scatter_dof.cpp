// The moderation's own degrees of freedom from the scatter of ln s² (docs/method.md §10):
// the inverse trigamma function against Boost's trigamma, the scatter against a brute-force
// weighted variance, the degrees of freedom it gives on normal and on heavy-tailed samples,
// and what the option does to the moderated variances.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <boost/math/special_functions/trigamma.hpp>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "scatter_dof.h"
#include "statmc/core/statistics_image.h"
#include "statmc/core/variance_filter.h"
#include "variance_filter_layout.h"

namespace statmc {
namespace {

TEST(ScatterDof, InverseTrigammaInvertsBoostsTrigamma)
{
    for (double x : {2e-4, 1e-2, 0.5, 1.0, 7.5, 31.5, 511.5, 1e4, 5e6}) {
        const double y = boost::math::trigamma(x);
        EXPECT_NEAR(detail::inverse_trigamma(y), x, 1e-4 * x) << x;
    }
}

// ln s² weighted by k(dx)·k(dy) over the square, straight from the definition.
double brute_force_scatter(const std::vector<double>& s2, int w, int h, int x, int y, int r,
                           double sigma)
{
    double sw = 0, sl = 0, sll = 0;
    for (int yy = std::max(y - r, 0); yy <= std::min(y + r, h - 1); ++yy)
        for (int xx = std::max(x - r, 0); xx <= std::min(x + r, w - 1); ++xx) {
            const double v = s2[std::size_t(yy) * w + xx];
            if (!(v > 0 && std::isfinite(v)))
                continue;
            const double k = std::exp(-double((xx - x) * (xx - x)) / (2 * sigma * sigma)) *
                             std::exp(-double((yy - y) * (yy - y)) / (2 * sigma * sigma));
            sw += k;
            sl += k * std::log(v);
            sll += k * std::log(v) * std::log(v);
        }
    if (!(sw > 0))
        return 0;
    const double mean = sl / sw, var = sll / sw - mean * mean;
    return var > 0 ? var : 0;
}

TEST(ScatterDof, TheScatterIsTheWeightedVarianceOfLnS2AtEveryPixelAndForAnyThreadCount)
{
    // Two channels, odd sizes, and pixels that do not count: NaN (unusable), 0, +∞.
    constexpr int w = 23, h = 17, r = 3;
    constexpr double sigma = 2;
    std::mt19937_64 rng(3);
    std::lognormal_distribution<double> spread(0.0, 1.5);
    detail::VarianceLayout L;
    L.width = w;
    L.height = h;
    L.channels = 2;
    L.pixels = std::size_t(w) * h;
    L.prior_s2.resize(2 * L.pixels);
    for (double& v : L.prior_s2)
        v = spread(rng);
    L.prior_s2[5] = NAN;
    L.prior_s2[40] = 0;
    L.prior_s2[L.pixels + 77] = INFINITY;
    // A corner whose square holds a single pixel that counts: no scatter there.
    for (int y = 0; y <= r; ++y)
        for (int x = 0; x <= r; ++x)
            L.prior_s2[std::size_t(y) * w + x] = (x == 0 && y == 0) ? 1.0 : NAN;
    const std::vector<float> scatter = detail::log_variance_scatter(L, r, sigma);
    for (int c = 0; c < 2; ++c) {
        const std::vector<double> plane(L.prior_s2.begin() + c * L.pixels,
                                        L.prior_s2.begin() + (c + 1) * L.pixels);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double want = brute_force_scatter(plane, w, h, x, y, r, sigma);
                const float got = scatter[c * L.pixels + std::size_t(y) * w + x];
                EXPECT_NEAR(got, want, 1e-5 * want + 1e-12) << c << ": " << x << "," << y;
            }
    }
    EXPECT_EQ(scatter[0], 0.f);
    EXPECT_EQ(detail::scatter_dof(scatter[0]), std::numeric_limits<double>::infinity());
    std::vector<float> one;
    tbb::task_arena(1).execute([&] { one = detail::log_variance_scatter(L, r, sigma); });
    EXPECT_EQ(one, scatter);
}

// n samples per pixel, each a hit of 1 with probability p and 0.5 ± 0.001 otherwise
// (p = 0: normal samples of σ = 0.1 around 0.5).
StatisticsPlanes samples(int w, int h, int n, double p, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution hit(p);
    std::normal_distribution<float> normal(0.5f, 0.1f);
    std::uniform_real_distribution<float> dim(0.499f, 0.501f);
    StatisticsImage<1> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < n; ++s) {
                const float v = p == 0 ? normal(rng) : (hit(rng) ? 1.f : dim(rng));
                img.add(x, y, &v);
            }
    return img.planes();
}

double median_dof(const StatisticsPlanes& stats)
{
    const StatisticsView view = stats.view();
    detail::VarianceLayout L;
    L.width = view.width;
    L.height = view.height;
    L.channels = 1;
    L.pixels = std::size_t(view.width) * view.height;
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x)
            L.prior_s2.push_back(view.variance[0](x, y));
    const std::vector<float> scatter = detail::log_variance_scatter(L, 3, 2.0);
    std::vector<double> dof;
    for (float s : scatter)
        dof.push_back(detail::scatter_dof(s));
    std::nth_element(dof.begin(), dof.begin() + dof.size() / 2, dof.end());
    return dof[dof.size() / 2];
}

TEST(ScatterDof, NormalSamplesGetTheirOwnDegreesOfFreedomAndHeavyTailsFarFewer)
{
    // Normal samples, n = 16: ln s² scatters with variance ψ'(15/2), so d ≈ 15. Each
    // pixel's scatter is a weighted variance of about 25 effective pixels (relative sd about
    // 0.3); the median over 4096 pixels (about 80 independent squares) has a relative sd near
    // 5%, so ±25% is 5 sd.
    EXPECT_NEAR(median_dof(samples(64, 64, 16, 0, 1)), 15, 0.25 * 15);
    // Rare hits (p = 0.03, n = 64): the excess kurtosis of such a sample is about 31, so
    // var(s²)/σ⁴ ≈ 2/63 + 31/64 and s² is worth about 4 degrees of freedom, not 63.
    EXPECT_LT(median_dof(samples(64, 64, 64, 0.03, 2)), 63.0 / 4);
}

TEST(ScatterDof, TheOptionOnlyEverLiftsAVarianceBelowItsPriorAndKeepsTheBitsAcrossThreads)
{
    const StatisticsPlanes stats = samples(40, 30, 64, 0.03, 5);
    VarianceFilterOptions off;
    off.prior_dof = 16;
    off.prior_alpha = 0.05;
    VarianceFilterOptions on = off;
    on.own_dof_from_scatter = true;
    const StatisticsView view = stats.view();
    const std::vector<float> before = denoise_variances(view, TestDomain::Untransformed, {}, off);
    const std::vector<float> after = denoise_variances(view, TestDomain::Untransformed, {}, on);
    // More weight on the prior, and only where the prior is the larger: never lower.
    std::size_t lifted = 0;
    for (std::size_t i = 0; i < after.size(); ++i) {
        EXPECT_GE(after[i], before[i]) << i;
        lifted += after[i] > before[i];
    }
    // Pixels without a hit (P = 0.97^64 = 14%) have an s² far below their prior.
    EXPECT_GT(lifted, after.size() / 20);
    EXPECT_EQ(after, denoise_variances(view, TestDomain::Untransformed, {}, on, 1));
    // Only some pixels wanted (a band of rows and a lone pixel): the same values there.
    PixelMask wanted(std::size_t(view.width) * view.height, 0);
    for (int x = 0; x < view.width; ++x)
        wanted[std::size_t(12) * view.width + x] = wanted[std::size_t(13) * view.width + x] = 1;
    wanted[std::size_t(25) * view.width + 7] = 1;
    const std::vector<float> some =
        denoise_variances(view, TestDomain::Untransformed, {}, on, 0, SimdLevel::Auto, wanted);
    for (std::size_t i = 0; i < wanted.size(); ++i) {
        if (wanted[i]) {
            EXPECT_EQ(some[i], after[i]) << i;
        }
    }
    for (SimdLevel level : supported_simd_levels())
        EXPECT_EQ(after, denoise_variances(view, TestDomain::Untransformed, {}, on, 2, level));
}

}  // namespace
}  // namespace statmc
