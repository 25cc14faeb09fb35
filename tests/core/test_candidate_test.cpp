// verify's test (candidate_test.h) against a brute-force reference of its documented rule,
// written pixel by pixel from the header's formulas with Boost's t quantiles: random
// images of odd sizes with untestable pixels (n < 2, NaN, negative or zero variances),
// every box radius from the pixel alone to one wider than the image, any thread count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <boost/math/distributions/students_t.hpp>
#include <gtest/gtest.h>

#include "statmc/core/candidate_test.h"

namespace statmc {
namespace {

constexpr int kChannels = 3;

struct Frame {
    int w, h;
    std::vector<float> count, mean, candidate, variance;  // planes channel-major

    StatisticsView view() const
    {
        StatisticsView v;
        v.width = w;
        v.height = h;
        v.channels = kChannels;
        v.count = dense_plane(count.data(), w);
        for (int c = 0; c < kChannels; ++c)
            v.mean[c] = dense_plane(mean.data() + std::size_t(c) * w * h, w);
        return v;
    }
    std::vector<ConstPlane> candidate_planes() const
    {
        std::vector<ConstPlane> planes;
        for (int c = 0; c < kChannels; ++c)
            planes.push_back(dense_plane(candidate.data() + std::size_t(c) * w * h, w));
        return planes;
    }
};

// Counts from 0 to 40; differences of a standard error, biased by 1.5 of them in the left
// half (which boxes see better than pixels) and by far more at one pixel in twenty; and
// about one pixel in twenty untestable in some channel.
Frame random_frame(int w, int h, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> counts(0, 40), one_in(0, 19);
    std::normal_distribution<float> z(0.f, 1.f);
    std::exponential_distribution<float> spread(1.f);
    const std::size_t pixels = std::size_t(w) * h;
    Frame f{w,
            h,
            std::vector<float>(pixels),
            std::vector<float>(pixels * kChannels),
            std::vector<float>(pixels * kChannels),
            std::vector<float>(pixels * kChannels)};
    for (std::size_t i = 0; i < pixels; ++i) {
        f.count[i] = float(counts(rng));
        for (int c = 0; c < kChannels; ++c) {
            const std::size_t k = c * pixels + i;
            const float s2 = spread(rng);
            f.variance[k] = s2;
            f.mean[k] = 1 + z(rng);
            const float se = std::sqrt(s2 / std::max(f.count[i], 1.f));
            const float bias = (2 * (i % w) < std::size_t(w) ? 1.5f : 0.f) + z(rng);
            f.candidate[k] = f.mean[k] + se * bias * (one_in(rng) == 0 ? 6.f : 1.f);
            switch (one_in(rng)) {
            case 0:
                f.mean[k] = std::numeric_limits<float>::quiet_NaN();
                break;
            case 1:
                f.variance[k] = -1.f;
                break;
            case 2:
                f.variance[k] = 0.f;
                break;
            default:
                break;
            }
        }
    }
    return f;
}

double critical(double alpha, double df)
{
    const boost::math::students_t t(std::max(1.0, std::floor(df)));
    return boost::math::quantile(boost::math::complement(t, alpha / 2));
}

// The rule of candidate_test.h, pixel by pixel, the box adding its testable pixels in
// raster order. (Where they have no spread, V = 0 and the df does not matter.)
std::vector<std::uint8_t> reference(const Frame& f, const CandidateTestOptions& o)
{
    const int w = f.w, h = f.h, b = o.box_radius;
    const std::size_t pixels = std::size_t(w) * h;
    const double alpha = o.alpha / ((b > 0 ? 2 : 1) * kChannels);
    auto tested = [&](std::size_t i, int c) {
        const double d = double(f.mean[c * pixels + i]) - f.candidate[c * pixels + i];
        const double s2 = f.variance[c * pixels + i];
        return f.count[i] >= 2 && std::isfinite(d) && std::isfinite(s2) && s2 >= 0;
    };
    std::vector<std::uint8_t> out(pixels, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            for (int c = 0; c < kChannels; ++c) {
                const double n = f.count[i], df = n - 1 + o.prior_dof;
                if (tested(i, c)) {
                    const double d = double(f.mean[c * pixels + i]) - f.candidate[c * pixels + i];
                    const double g = critical(alpha, df);
                    if (d * d > g * g * (f.variance[c * pixels + i] / n))
                        out[i] |= kRejectedByPixel;
                }
                if (b == 0)
                    continue;
                double sum = 0, v = 0, v2_over_df = 0;
                int k = 0;
                for (int yy = std::max(0, y - b); yy <= std::min(h - 1, y + b); ++yy)
                    for (int xx = std::max(0, x - b); xx <= std::min(w - 1, x + b); ++xx) {
                        const std::size_t j = std::size_t(yy) * w + xx;
                        if (!tested(j, c))
                            continue;
                        const double nj = f.count[j], vj = f.variance[c * pixels + j] / nj;
                        sum += double(f.mean[c * pixels + j]) - f.candidate[c * pixels + j];
                        v += vj;
                        v2_over_df += vj * vj / (nj - 1 + o.prior_dof);
                        ++k;
                    }
                if (k == 0)
                    continue;
                const double mean = sum / k, var = v / (double(k) * k);
                const double box_df = v2_over_df > 0 ? v * v / v2_over_df : df;
                const double g = critical(alpha, std::max(box_df, 1.0));
                if (mean * mean > g * g * var)
                    out[i] |= kRejectedByBox;
            }
        }
    return out;
}

TEST(CandidateTest, GivesTheBruteForceRulesVerdictsForEveryBoxAndThreadCount)
{
    for (const auto& [w, h] : {std::pair{23, 17}, std::pair{1, 9}, std::pair{40, 3}})
        for (int box : {0, 1, 2, w + 1}) {
            const Frame f = random_frame(w, h, std::uint64_t(100 * w + box));
            CandidateTestOptions o;
            o.alpha = 0.05;  // many rejections, so that the comparison sees both verdicts
            o.box_radius = box;
            const std::vector<std::uint8_t> expected = reference(f, o);
            for (int threads : {1, 2}) {
                const std::vector<std::uint8_t> got =
                    test_candidate(f.view(), f.variance, f.candidate_planes(), o, threads);
                EXPECT_EQ(got, expected)
                    << w << "x" << h << ", box " << box << ", " << threads << " threads";
            }
            const auto rejected = [](std::uint8_t bits, std::uint8_t which) {
                return (bits & which) != 0;
            };
            EXPECT_GT(std::count_if(expected.begin(), expected.end(),
                                    [&](std::uint8_t v) { return rejected(v, kRejectedByPixel); }),
                      0);
            if (box > 0) {
                EXPECT_GT(
                    std::count_if(expected.begin(), expected.end(),
                                  [&](std::uint8_t v) { return rejected(v, kRejectedByBox); }),
                    0);
            }
        }
}

}  // namespace
}  // namespace statmc
