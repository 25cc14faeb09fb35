// Random estimator images and guides for comparing filter paths (SIMD levels, the double
// reference, the GPU), and the outputs they write. Header-only; core only.
#pragma once

#include <cmath>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/filter.h"

namespace statmc {

struct Output {
    int w, h, c;
    std::vector<float> values, members, weights, effective;
    Output(int w_, int h_, int c_)
        : w(w_), h(h_), c(c_), values(std::size_t(w) * h * c), members(std::size_t(w) * h),
          weights(std::size_t(w) * h), effective(std::size_t(w) * h)
    {
    }
    std::vector<Plane> planes()
    {
        std::vector<Plane> p;
        for (int k = 0; k < c; ++k)
            p.push_back(dense_plane(values.data() + std::size_t(k) * w * h, w));
        return p;
    }
    FilterDiagnostics diagnostics()
    {
        return {dense_plane(members.data(), w), dense_plane(weights.data(), w),
                dense_plane(effective.data(), w)};
    }
};

// Random estimators with region structure, so that the test both accepts and rejects,
// and a few fireflies, so that the firefly guard's second step is compared too.
inline EstimatorImage random_estimators(int w, int h, int channels, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    EstimatorImage est(w, h, channels);
    est.domain = TestDomain::BoxCox;  // so that the firefly guard takes part
    est.support.assign(est.pixels(), 1.f);  // fireflies below get support ≥ 2 in part
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            est.count[est.index(0, x, y)] = float(2 + rng() % 64);
            const float level = ((x / 5 + y / 4) % 3) * 0.5f;
            for (int c = 0; c < channels; ++c) {
                const std::size_t i = est.index(c, x, y);
                est.value[i] = level + 0.2f * u(rng);
                est.test_mean[i] = level + 0.1f * u(rng);
                est.test_variance[i] = 0.002f * u(rng);
            }
            if (rng() % 23 == 0)  // a few untestable pixels
                est.test_variance[est.index(0, x, y)] = NAN;
            else if (rng() % 31 == 0) {  // a few fireflies, half of them glints (support 3)
                for (int c = 0; c < channels; ++c) {
                    est.value[est.index(c, x, y)] += 40.f;
                    est.test_mean[est.index(c, x, y)] += 0.5f;
                    est.test_variance[est.index(c, x, y)] *= 3000.f;
                }
                est.support[std::size_t(y) * w + x] = rng() % 2 ? 3.f : 1.f;
            }
        }
    return est;
}

struct GuideImages {
    std::vector<float> data, variance;
    Guides guides;
    /// `noise`: also the guides' per-sample variances, at a size that makes some guide
    /// distances wholly and some partly explained by noise (filter_layout.h), and 0 on
    /// every fifth pixel.
    GuideImages(int w, int h, bool albedo, bool normal, std::uint64_t seed, bool noise = false)
        : data(std::size_t(w) * h * 6), variance(std::size_t(w) * h * 2)
    {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<float> u(0.f, 1.f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < 6; ++k)
                    data[std::size_t(k) * w * h + std::size_t(y) * w + x] =
                        ((x / 7) % 2) * 0.05f + 0.03f * u(rng) + 0.1f * k;
        for (int k = 0; k < 3; ++k) {
            if (albedo)
                guides.albedo[k] = dense_plane(data.data() + std::size_t(k) * w * h, w);
            if (normal)
                guides.normal[k] = dense_plane(data.data() + std::size_t(k + 3) * w * h, w);
        }
        if (!noise)
            return;
        for (std::size_t i = 0; i < variance.size(); ++i)
            variance[i] = i % 5 == 0 ? 0.f : 0.4f * u(rng);
        if (albedo)
            guides.albedo_variance = dense_plane(variance.data(), w);
        if (normal)
            guides.normal_variance = dense_plane(variance.data() + std::size_t(w) * h, w);
    }
};

/// One shape the filter paths are compared on: size, channels, radius and guides.
struct FilterCase {
    int w, h, channels, radius;
    bool albedo, normal;
    bool guide_noise = false;  ///< the guides come with their variances
};

inline void PrintTo(const FilterCase& k, std::ostream* os)
{
    *os << k.w << "x" << k.h << ", " << k.channels << " channels, r " << k.radius;
}

/// The shapes every filter path is compared on, plus `more`: borders and sizes that are
/// not a multiple of a SIMD width or a GPU block, r = 0, r larger than the image, one pixel,
/// one column, one and four channels, and each guide.
inline std::vector<FilterCase> filter_cases(std::vector<FilterCase> more = {})
{
    std::vector<FilterCase> cases = {
        {37, 23, 3, 5, false, false},      {37, 23, 3, 0, false, false},
        {9, 6, 3, 20, false, false},       {1, 1, 3, 20, false, false},
        {1, 17, 3, 4, false, false},       {40, 3, 1, 6, false, false},
        {24, 16, 4, 6, false, false},      {33, 19, 3, 6, true, false},
        {33, 19, 3, 6, false, true},       {33, 19, 3, 6, true, true},
        {33, 19, 3, 6, true, false, true}, {33, 19, 3, 6, true, true, true}};
    cases.insert(cases.end(), more.begin(), more.end());
    return cases;
}

/// The test's name for a case: "37x23_c3_r5_albedo".
inline std::string case_name(const ::testing::TestParamInfo<FilterCase>& info)
{
    const FilterCase& k = info.param;
    return std::to_string(k.w) + "x" + std::to_string(k.h) + "_c" + std::to_string(k.channels) +
           "_r" + std::to_string(k.radius) + (k.albedo ? "_albedo" : "") +
           (k.normal ? "_normal" : "") + (k.guide_noise ? "_noise" : "");
}

/// The options the cases run at: the case's radius, and falloffs that the fixtures'
/// guides and distances make matter.
inline DenoiseOptions case_options(const FilterCase& k)
{
    DenoiseOptions opt;
    opt.radius = k.radius;
    opt.sigma_spatial = 3.f;
    opt.sigma_albedo = 0.05f;
    opt.sigma_normal = 0.2f;
    return opt;
}

/// How far two filter paths may differ: values relative to 1 + |value|, weights and
/// effective sample counts relative.
struct Tolerance {
    float value, weight, effective;
};

/// Members must agree exactly; values, weights and effective sample counts within `t`
/// (summation order and precision differ between the paths).
inline void expect_same_members(const Output& out, const Output& ref, Tolerance t)
{
    for (std::size_t i = 0; i < ref.members.size(); ++i)
        ASSERT_EQ(out.members[i], ref.members[i]) << "members of pixel " << i;
    for (std::size_t i = 0; i < ref.values.size(); ++i)
        ASSERT_NEAR(out.values[i], ref.values[i], t.value * (1 + std::abs(ref.values[i])))
            << "value " << i;
    for (std::size_t i = 0; i < ref.weights.size(); ++i)
        ASSERT_NEAR(out.weights[i], ref.weights[i], t.weight * ref.weights[i]) << "weight " << i;
    for (std::size_t i = 0; i < ref.effective.size(); ++i)
        ASSERT_NEAR(out.effective[i], ref.effective[i], t.effective * ref.effective[i])
            << "effective samples " << i;
}

}  // namespace statmc
