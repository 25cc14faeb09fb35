// The residual check (docs/method.md §17): where what a denoise took out of a window is
// larger than the noisy means' noise explains, the output is pulled back towards the noisy
// means; elsewhere it keeps its bits.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/residual_check.h"
#include "statmc/core/statistics_image.h"
#include "window_fixtures.h"

namespace statmc {
namespace {

using namespace window_fixtures;

constexpr ResidualCheckOptions kCheck{3, 0.005};

float step(int x, int, int c) { return x < 32 ? 4.f + c : 8.f + c; }

// The rule of residual_check.h written out window by window, each sum in the order the
// check adds it (a column of the window at a time, top to bottom, columns left to right).
std::vector<float> brute_force(const StatisticsPlanes& s, std::vector<float> out,
                               const ResidualCheckOptions& o, bool variance_of_mean)
{
    const int w = s.width, h = s.height, r = o.radius;
    const std::size_t n = std::size_t(w) * h;
    const double z = normal_critical_value(o.alpha), window = double(2 * r + 1) * (2 * r + 1);
    for (int c = 0; c < s.channels; ++c) {
        std::vector<double> res(n), var(n), share(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double m = s.mean[c * n + i], o_i = out[c * n + i], cnt = s.count[i];
            const double s2 = s.variance[c * n + i], v = variance_of_mean ? s2 : s2 / cnt;
            const bool usable = cnt >= 2 && std::isfinite(m) && std::isfinite(o_i);
            res[i] = usable ? o_i - m : 0.0;
            var[i] = usable && std::isfinite(v) && v > 0 ? v : 0.0;
        }
        auto box = [&](int x, int y, auto term) {
            double sum = 0;
            for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
                double column = 0;
                for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
                    column += term(std::size_t(yy) * w + xx);
                sum += column;
            }
            return sum;
        };
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double d = box(x, y, [&](std::size_t i) { return res[i] * res[i]; });
                const double v = box(x, y, [&](std::size_t i) { return var[i]; });
                const double q = box(x, y, [&](std::size_t i) { return var[i] * var[i]; });
                share[std::size_t(y) * w + x] = d > v + z * std::sqrt(2 * q) ? 1 - v / d : 0.0;
            }
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const double g = box(x, y, [&](std::size_t j) { return share[j]; }) / window;
                if (g > 0 && res[i] != 0)
                    out[c * n + i] = float(out[c * n + i] - g * res[i]);
            }
    }
    return out;
}

TEST(ResidualCheck, AnOutputOfTheNoisyMeansKeepsItsBits)
{
    const StatisticsPlanes s = noisy_means(flat, 1);
    std::vector<float> out = s.mean;
    EXPECT_EQ(keep_window_residual(s.view(), planes_of(out), kCheck), 0u);
    EXPECT_EQ(out, s.mean);
}

TEST(ResidualCheck, GivesTheRuleWrittenOutWindowByWindowForAnySizeAndRadius)
{
    // Random means, variances and counts (some n < 2, some means not finite), an output
    // that blurs and biases them so that some windows are off; odd sizes, a radius of 1,
    // and radii beyond the image.
    const std::vector<std::array<int, 3>> cases = {
        {37, 23, 1}, {37, 23, 3}, {5, 3, 2}, {1, 1, 1}, {9, 7, 40}};
    for (const std::array<int, 3>& sizes : cases) {
        const int w = sizes[0], h = sizes[1], r = sizes[2];
        for (const bool variance_of_mean : {false, true}) {
            std::mt19937_64 rng(std::uint64_t(w * 1000 + h * 10 + r + variance_of_mean));
            std::uniform_real_distribution<float> u(0.f, 1.f);
            StatisticsPlanes s = noisy_means(step, 7, w, h);
            const std::size_t n = std::size_t(w) * h;
            for (std::size_t i = 0; i < n; ++i)
                s.count[i] = u(rng) < 0.05f ? 1.f : float(2 + int(30 * u(rng)));
            for (float& v : s.variance)
                v = 0.1f + 4 * u(rng) * u(rng);
            s.mean[n / 2] = std::numeric_limits<float>::quiet_NaN();
            std::vector<float> out(s.mean.size());
            for (std::size_t i = 0; i < out.size(); ++i)
                out[i] = 0.5f * s.mean[i] + 0.5f * s.mean[(i / n) * n + (i % n + 1) % n] +
                         (u(rng) < 0.3f ? 2.f : 0.f);
            out[0] = std::numeric_limits<float>::infinity();
            const std::vector<float> expected = brute_force(s, out, {r, 0.005}, variance_of_mean);
            StatisticsView view = s.view();
            view.variance_of_mean = variance_of_mean;
            keep_window_residual(view, planes_of(out, w, h), {r, 0.005});
            for (std::size_t i = 0; i < out.size(); ++i) {
                if (std::isnan(expected[i])) {
                    ASSERT_TRUE(std::isnan(out[i])) << w << "x" << h << " r " << r << " at " << i;
                    continue;
                }
                ASSERT_EQ(out[i], expected[i]) << w << "x" << h << " r " << r << " at " << i;
            }
        }
    }
}

TEST(ResidualCheck, PullsASmearedEdgeBackTowardsTheNoisyMeans)
{
    // An output that smeared a step of 4 across the 8 pixels around it and left the noisy
    // means elsewhere: in the smear its residuals are up to 2, against a noise of 0.25 per
    // pixel, so the windows there are off and the smear goes back most of the way to the
    // noisy means, whose error is that noise. Every pixel outside it, whose residual is 0,
    // keeps its bits.
    const StatisticsPlanes s = noisy_means(step, 2);
    const std::size_t n = std::size_t(kW) * kH;
    auto smeared = [](int x) { return x >= 28 && x < 36; };
    std::vector<float> out = s.mean;
    for (int c = 0; c < kChannels; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                if (smeared(x))
                    out[c * n + std::size_t(y) * kW + x] = (4.f + c) + 4.f * (x - 27.5f) / 8.f;
    const std::vector<float> before = out;
    EXPECT_GT(keep_window_residual(s.view(), planes_of(out), kCheck), 0u);
    double error_before = 0, error_after = 0, error_noisy = 0;
    for (int c = 0; c < kChannels; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const std::size_t i = c * n + std::size_t(y) * kW + x;
                if (!smeared(x)) {
                    ASSERT_EQ(out[i], before[i]) << "at " << x << "," << y;
                    continue;
                }
                const double t = step(x, y, c);
                error_before += (before[i] - t) * (before[i] - t);
                error_after += (out[i] - t) * (out[i] - t);
                error_noisy += (s.mean[i] - t) * (s.mean[i] - t);
            }
    EXPECT_LT(error_after, 0.25 * error_before);
    EXPECT_LT(error_after, 2 * error_noisy);
}

TEST(ResidualCheck, FindsAnUnbiasedOutputOffAtTheChiSquaresRate)
{
    // The output is the truth itself, so each window's residuals are the noisy means'
    // normal errors of exactly the stated variances: D/(σ²/n) is χ² with as many degrees of
    // freedom as the window has pixels, and the test's normal approximation of its tail
    // finds a window off with probability 0.0068 (49 pixels) to 0.0104 (16, a corner).
    // Over five seeds of 3 × 64 × 48 windows, whose verdicts come in clusters of a few
    // dozen at most, the count stays within [0.0068·N/3, 2·0.0104·N] but for a chance well
    // below one in a thousand. And what those false alarms give back of the noise costs
    // under 1% of the noisy means' squared error.
    const double windows = 5.0 * kChannels * kW * kH;
    double off = 0, error = 0, noisy_error = 0;
    for (std::uint64_t seed = 10; seed < 15; ++seed) {
        const StatisticsPlanes s = noisy_means(flat, seed);
        std::vector<float> out(s.mean.size());
        for (int c = 0; c < kChannels; ++c)
            std::fill(out.begin() + std::size_t(c) * kW * kH,
                      out.begin() + std::size_t(c + 1) * kW * kH, flat(0, 0, c));
        off += double(keep_window_residual(s.view(), planes_of(out), kCheck));
        for (std::size_t i = 0; i < out.size(); ++i) {
            const double t = flat(0, 0, int(i / (std::size_t(kW) * kH)));
            error += (out[i] - t) * (out[i] - t);
            noisy_error += (s.mean[i] - t) * (s.mean[i] - t);
        }
    }
    EXPECT_LE(off, 2 * 0.0104 * windows);
    EXPECT_GE(off, 0.0068 * windows / 3);
    EXPECT_LT(error, 0.01 * noisy_error);
}

TEST(ResidualCheck, IsTheSameForAnyThreadCountAndReadsTheOutputWithinTwiceItsRadius)
{
    // At (30, 20), by the smeared edge.
    const StatisticsPlanes s = noisy_means(step, 3);
    expect_thread_count_free_and_local(keep_window_residual, kCheck, s,
                                       blended_with_shift(s.mean, 0.5f, 2), 30, 20,
                                       2 * kCheck.radius);
}

TEST(ResidualCheck, BadOptionsAndMissingPlanesAreErrors)
{
    expect_bad_options_and_missing_planes_are_errors<ResidualCheckOptions>(keep_window_residual);
}

}  // namespace
}  // namespace statmc
