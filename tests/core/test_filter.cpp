// The optimised filter against the plain reference of docs/method.md §5, and its invariants.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "estimator_fixtures.h"
#include "filter_fixtures.h"
#include "filter_layout.h"
#include "statmc/core/filter.h"
#include "statmc/core/firefly_guard.h"

namespace statmc {
namespace {

// Against the double reference: members exactly, values up to float accumulation.
void expect_agree(const Output& fast, const Output& ref)
{
    expect_same_members(fast, ref, {2e-5f, 1e-4f, 2e-4f});
}

void expect_matches_reference(const EstimatorImage& est, const Guides& guides,
                              const DenoiseOptions& opt, SimdLevel level)
{
    Output fast(est.width, est.height, est.channels), ref(est.width, est.height, est.channels);
    filter(est, guides, opt, fast.planes(), fast.diagnostics(), 0, level);
    filter_reference(est, guides, opt, ref.planes(), ref.diagnostics());
    expect_agree(fast, ref);
}

class FilterVsReference : public ::testing::TestWithParam<FilterCase> {};

TEST_P(FilterVsReference, Agree)
{
    const FilterCase k = GetParam();
    const EstimatorImage est = random_estimators(k.w, k.h, k.channels, 100 + k.w + k.radius);
    GuideImages g(k.w, k.h, k.albedo, k.normal, 7, k.guide_noise);
    DenoiseOptions opt = case_options(k);
    for (SimdLevel level : supported_simd_levels()) {
        SCOPED_TRACE(simd_level_name(level));
        expect_matches_reference(est, g.guides, opt, level);
    }
}

INSTANTIATE_TEST_SUITE_P(Shapes, FilterVsReference,
                         // and r = 1, and the channel counts of joint AOVs
                         ::testing::ValuesIn(filter_cases({{37, 23, 3, 1, false, false},
                                                           {29, 17, 6, 4, true, true},
                                                           {29, 17, 9, 4, false, false},
                                                           {21, 13, 12, 3, true, false, true}})),
                         case_name);

TEST(Filter, TheFixturesFirefliesAreGuardedAgainst)
{
    // Each injected firefly presents a level above the limit of its neighbours, so the
    // comparisons with the reference cover the guard.
    const EstimatorImage est = random_estimators(37, 23, 3, 105);
    const NoiseLevels noise = noise_levels(est, DenoiseOptions{}.firefly_ratio);
    int refused = 0;
    for (int y = 1; y + 1 < est.height; ++y)
        for (int x = 1; x + 1 < est.width; ++x)
            refused += noise.level[std::size_t(y) * est.width + x] >
                       noise.limit[std::size_t(y) * est.width + x + 1];
    EXPECT_GT(refused, 5);
}

// Guide noise (docs/method.md §5): centre i weighs j by spatial · exp(−max(0, D − U)),
// D = Σ_guides |g_i − g_j|²/(2σ²) and U = 2·min(u_i, u_j), u = Σ_guides (s²/n)/(2σ²): the
// less noisy side's noise explains the distance away, so i weighs j exactly as j weighs i
// (a noisy pixel cannot take neighbours that do not take it, and lose its light). Two
// pixels that the test cannot tell apart, so pixel i's output is (F_i + w F_j)/(1 + w).
TEST(Filter, GuideNoiseTakesWhatItExplainsOutOfTheGuideDistance)
{
    EstimatorImage est(2, 1, 1);
    est.domain = TestDomain::BoxCox;
    const float values[2] = {1.f, 3.f}, counts[2] = {4.f, 8.f};
    for (int x = 0; x < 2; ++x) {
        est.count[x] = counts[x];
        est.value[x] = values[x];
        est.test_mean[x] = 1.f;
        est.test_variance[x] = 0.01f;
    }
    const float albedo[2] = {0.2f, 0.3f};  // D = 3 · 0.01/(2 · 0.05²) = 6
    const float normal[2] = {0.f, 0.f};
    DenoiseOptions opt;
    opt.radius = 1;
    opt.sigma_spatial = 2.f;
    opt.sigma_albedo = 0.05f;
    opt.firefly_ratio = 0;
    const double spatial = std::exp(-1.0 / (2 * 2.0 * 2.0)), falloff = 1 / (2 * 0.05 * 0.05);
    for (const float s2 : {0.f, 0.02f, 0.2f}) {  // U = 0, about 1.5 (partly), 15 (wholly)
        SCOPED_TRACE("s² = " + std::to_string(s2));
        const float variance[2] = {s2, s2};
        Guides g;
        for (int c = 0; c < 3; ++c) {
            g.albedo[c] = dense_plane(albedo, 2);
            g.normal[c] = dense_plane(normal, 2);
        }
        g.albedo_variance = dense_plane(variance, 2);
        const double D = 3 * 0.1 * 0.1 * falloff, u0 = s2 / 4 * falloff, u1 = s2 / 8 * falloff;
        const double w0 = spatial * std::exp(-std::max(0.0, D - 2 * std::min(u0, u1)));
        const double w1 = spatial * std::exp(-std::max(0.0, D - 2 * std::min(u1, u0)));
        for (SimdLevel level : supported_simd_levels()) {
            SCOPED_TRACE(simd_level_name(level));
            Output fast(2, 1, 1), ref(2, 1, 1);
            filter(est, g, opt, fast.planes(), fast.diagnostics(), 1, level);
            filter_reference(est, g, opt, ref.planes(), ref.diagnostics());
            EXPECT_NEAR(fast.values[0], (1 + w0 * 3) / (1 + w0), 2e-6);
            EXPECT_NEAR(fast.values[1], (3 + w1 * 1) / (1 + w1), 2e-6);
            EXPECT_NEAR(ref.values[0], (1 + w0 * 3) / (1 + w0), 1e-6);
            EXPECT_NEAR(ref.values[1], (3 + w1 * 1) / (1 + w1), 1e-6);
            EXPECT_NEAR(fast.weights[0], 1 + w0, 2e-6);
            EXPECT_NEAR(fast.weights[1], 1 + w1, 2e-6);
            EXPECT_EQ(fast.weights[0], fast.weights[1]);  // the same weight both ways
        }
    }
}

// Without the guides' variances the kernel adds u = 0 and keeps the sum; so an image
// without them, and one with all-zero ones, give the same bits as the filter before guide
// noise existed (method=classic on old files).
TEST(Filter, ZeroGuideVariancesAreBitwiseNoGuideVariances)
{
    const EstimatorImage est = random_estimators(77, 41, 3, 13);
    GuideImages without(77, 41, true, true, 5);
    GuideImages zero(77, 41, true, true, 5, /*noise=*/true);
    std::fill(zero.variance.begin(), zero.variance.end(), 0.f);
    DenoiseOptions opt;
    opt.radius = 7;
    for (SimdLevel level : supported_simd_levels()) {
        SCOPED_TRACE(simd_level_name(level));
        Output a(77, 41, 3), b(77, 41, 3);
        filter(est, without.guides, opt, a.planes(), a.diagnostics(), 0, level);
        filter(est, zero.guides, opt, b.planes(), b.diagnostics(), 0, level);
        EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * 4), 0);
        EXPECT_EQ(std::memcmp(a.weights.data(), b.weights.data(), a.weights.size() * 4), 0);
    }
}

// side_by_side (joint AOVs): one filter over two images accepts a neighbour only where both
// tests do. Over an image and itself that is its own test: the same members and values.
TEST(Filter, SideBySideAcceptsWhereEveryPartAccepts)
{
    const EstimatorImage a = random_estimators(41, 27, 3, 31), b = random_estimators(41, 27, 3, 32);
    EstimatorImage b_counted = b;
    b_counted.count = a.count;  // parts share their counts
    DenoiseOptions opt = case_options({41, 27, 3, 6, false, false});
    // The firefly guard compares each pixel's largest level over all its channels, which is
    // not the AND of the parts' guards; the t-tests are.
    opt.firefly_ratio = 0;
    for (SimdLevel level : supported_simd_levels()) {
        SCOPED_TRACE(simd_level_name(level));
        Output alone(41, 27, 3), twice(41, 27, 6), other(41, 27, 3), both(41, 27, 6);
        filter(a, {}, opt, alone.planes(), alone.diagnostics(), 0, level);
        filter(side_by_side({&a, &a}), {}, opt, twice.planes(), twice.diagnostics(), 0, level);
        filter(b_counted, {}, opt, other.planes(), other.diagnostics(), 0, level);
        filter(side_by_side({&a, &b_counted}), {}, opt, both.planes(), both.diagnostics(), 0,
               level);
        EXPECT_EQ(twice.members, alone.members);
        for (std::size_t i = 0; i < alone.values.size(); ++i)
            ASSERT_NEAR(twice.values[i], alone.values[i], 1e-6f * (1 + std::abs(alone.values[i])));
        int fewer = 0;
        for (std::size_t i = 0; i < alone.members.size(); ++i) {
            ASSERT_LE(both.members[i], std::min(alone.members[i], other.members[i])) << i;
            fewer += both.members[i] < alone.members[i];
        }
        EXPECT_GT(fewer, 0);
    }
    EXPECT_THROW(side_by_side({&a, &b}), std::invalid_argument);  // other counts
    const EstimatorImage five = random_estimators(41, 27, 5, 33);
    EXPECT_THROW(filter(five, {}, opt, Output(41, 27, 5).planes()), std::invalid_argument);
}

TEST(Filter, BitwiseIdenticalForAnyThreadCount)
{
    const EstimatorImage est = random_estimators(150, 97, 3, 3);
    GuideImages g(150, 97, true, true, 4, /*noise=*/true);
    DenoiseOptions opt;
    opt.radius = 9;
    Output one(150, 97, 3), two(150, 97, 3), all(150, 97, 3);
    filter(est, g.guides, opt, one.planes(), one.diagnostics(), 1);
    filter(est, g.guides, opt, two.planes(), two.diagnostics(), 2);
    filter(est, g.guides, opt, all.planes(), all.diagnostics(), 0);
    EXPECT_EQ(std::memcmp(one.values.data(), two.values.data(), one.values.size() * 4), 0);
    EXPECT_EQ(std::memcmp(one.values.data(), all.values.data(), one.values.size() * 4), 0);
    EXPECT_EQ(std::memcmp(one.weights.data(), two.weights.data(), one.weights.size() * 4), 0);
    EXPECT_EQ(std::memcmp(one.effective.data(), all.effective.data(), one.effective.size() * 4), 0);
}

// A tap whose guides agree exactly in every lane takes its weight from a table
// (FilterLayout::flat_guide_weight) instead of the exp; the table must hold the exp's own
// bits. Guides `flat`: the first constant over 8-pixel stripes, the rest constant, so most
// taps take the table. Guides `nudged` move every third pixel's last guide (summed apart
// from the first, filter_kernel.h) by ~3·10⁻⁷ relative, in the kernel's scaled planes too:
// its squared distance becomes ~10⁻¹², far below half an ulp of every log-weight at
// σ_s = 10, so the exponents are the same floats, but those taps take the exp. The two
// must agree bit for bit for each guide set, guide noise or not, for the plain filter and
// the ladder's rungs.
TEST(Filter, FlatGuidesTakeTheExpsBits)
{
    constexpr int w = 77, h = 41;
    const EstimatorImage est = random_estimators(w, h, 3, 17);
    for (auto [albedo, normal] : {std::pair{true, true}, {true, false}, {false, true}})
        for (bool noise : {false, true}) {
            GuideImages flat(w, h, albedo, normal, 6, noise),
                nudged(w, h, albedo, normal, 6, noise);
            const int first = albedo ? 0 : 3, last = normal ? 5 : 2;
            for (int k = 0; k < 6; ++k)
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        const std::size_t i = std::size_t(k) * w * h + std::size_t(y) * w + x;
                        flat.data[i] = nudged.data[i] =
                            0.3f + 0.1f * k + (k == first) * 0.05f * ((x / 8) % 2);
                        if (k == last && (x + y) % 3 == 0)
                            nudged.data[i] *= 1.f + 3e-7f;
                    }
            DenoiseOptions opt;
            opt.radius = 7;
            for (SimdLevel level : supported_simd_levels()) {
                SCOPED_TRACE(std::string(simd_level_name(level)) + (albedo ? " albedo" : "") +
                             (normal ? " normal" : "") + (noise ? ", guide noise" : ""));
                // The nudge survives the scaling into the kernel's planes, so those taps do
                // not take the table.
                const detail::FilterLayout layout = detail::make_filter_layout(
                    est, nudged.guides, opt, {}, 1, detail::filter_kernel(level));
                const float* nudged_plane = layout.guide[layout.guide_count - 1];
                int apart = 0;
                for (int y = 0; y < h; ++y)
                    for (int x = 1; x < w; ++x)
                        apart += nudged_plane[std::ptrdiff_t(y) * layout.stride + x] !=
                                 nudged_plane[std::ptrdiff_t(y) * layout.stride + x - 1];
                EXPECT_GT(apart, w * h / 2);

                Output a(w, h, 3), b(w, h, 3), rungs_a(w, h, 3), rungs_b(w, h, 3);
                filter(est, flat.guides, opt, a.planes(), a.diagnostics(), 0, level);
                filter(est, nudged.guides, opt, b.planes(), b.diagnostics(), 0, level);
                EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * 4), 0);
                EXPECT_EQ(std::memcmp(a.weights.data(), b.weights.data(), a.weights.size() * 4),
                          0);
                EXPECT_EQ(
                    std::memcmp(a.effective.data(), b.effective.data(), a.effective.size() * 4),
                    0);
                const std::vector<int> radii = {2, 5, 7};
                detail::filter_rungs(est, flat.guides, opt, radii, rungs_a.planes(),
                                     rungs_a.diagnostics(), 0, level, [](int) {});
                detail::filter_rungs(est, nudged.guides, opt, radii, rungs_b.planes(),
                                     rungs_b.diagnostics(), 0, level, [](int) {});
                EXPECT_EQ(std::memcmp(rungs_a.values.data(), rungs_b.values.data(),
                                      rungs_a.values.size() * 4),
                          0);
            }
        }
}

TEST(Filter, DenseAndInterleavedOutputPlanesGetTheSameBits)
{
    // The kernel stores a whole chunk into dense planes as vectors and writes any other
    // layout lane by lane; both must give the same bits, diagnostics included, also in the
    // last, partial chunk of a row (a width that is no multiple of any SIMD width).
    const int w = 53, h = 19, channels = 3;
    EstimatorImage est = random_estimators(w, h, channels, 5);
    for (std::size_t i = 7; i < est.pixels(); i += 97)
        est.count[i] = 0;  // effective count 0, in full chunks and partial ones
    for (bool guided : {false, true}) {
        GuideImages g(w, h, guided, guided, 6, /*noise=*/guided);
        DenoiseOptions opt;
        opt.radius = 6;
        for (SimdLevel level : supported_simd_levels()) {
            SCOPED_TRACE(std::string(guided ? "guided, " : "unguided, ") + "level " +
                         std::to_string(int(level)));
            Output dense(w, h, channels);
            filter(est, g.guides, opt, dense.planes(), dense.diagnostics(), 0, level);
            // Interleaved: channels, members, weights and effective counts of a pixel side
            // by side, as in an image buffer.
            constexpr int kPlanes = channels + 3;
            std::vector<float> mixed(std::size_t(w) * h * kPlanes, -1.f);
            auto plane = [&](int k) {
                return Plane{mixed.data() + k, kPlanes, std::ptrdiff_t(kPlanes) * w};
            };
            std::vector<Plane> values;
            for (int c = 0; c < channels; ++c)
                values.push_back(plane(c));
            filter(est, g.guides, opt, values,
                   {plane(channels), plane(channels + 1), plane(channels + 2)}, 0, level);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    for (int c = 0; c < channels; ++c)
                        ASSERT_EQ(std::memcmp(&dense.values[c * w * h + i], &plane(c)(x, y), 4), 0)
                            << "value " << c << " at " << x << "," << y;
                    ASSERT_EQ(std::memcmp(&dense.members[i], &plane(channels)(x, y), 4), 0);
                    ASSERT_EQ(std::memcmp(&dense.weights[i], &plane(channels + 1)(x, y), 4), 0);
                    ASSERT_EQ(std::memcmp(&dense.effective[i], &plane(channels + 2)(x, y), 4), 0)
                        << "effective count at " << x << "," << y;
                }
        }
    }
}

TEST(Filter, VectorKernelsAgree)
{
    // Without guides AVX2 and AVX-512 run the same operations per lane (masked forms
    // included), so they must agree bit for bit. With guides only the exp's final power of
    // two is applied differently: same members, weights within a few ulp.
    const std::vector<SimdLevel> levels = supported_simd_levels();
    if (levels.back() != SimdLevel::Avx512)
        GTEST_SKIP() << "this CPU has no AVX-512";
    const EstimatorImage est = random_estimators(77, 41, 3, 11);
    for (bool guided : {false, true}) {
        SCOPED_TRACE(guided ? "guided" : "unguided");
        GuideImages g(77, 41, guided, guided, 5, /*noise=*/guided);
        DenoiseOptions opt;
        opt.radius = 7;
        Output avx2(77, 41, 3), avx512(77, 41, 3);
        filter(est, g.guides, opt, avx2.planes(), avx2.diagnostics(), 0, SimdLevel::Avx2);
        filter(est, g.guides, opt, avx512.planes(), avx512.diagnostics(), 0, SimdLevel::Avx512);
        EXPECT_EQ(avx2.members, avx512.members);
        if (!guided) {
            EXPECT_EQ(std::memcmp(avx2.values.data(), avx512.values.data(), avx2.values.size() * 4),
                      0);
            EXPECT_EQ(
                std::memcmp(avx2.weights.data(), avx512.weights.data(), avx2.weights.size() * 4),
                0);
            continue;
        }
        for (std::size_t i = 0; i < avx2.weights.size(); ++i)
            ASSERT_NEAR(avx512.weights[i], avx2.weights[i], 1e-6f * avx2.weights[i])
                << "weight " << i;
        for (std::size_t i = 0; i < avx2.values.size(); ++i)
            ASSERT_NEAR(avx512.values[i], avx2.values[i], 1e-6f * (1 + std::abs(avx2.values[i])))
                << "value " << i;
    }
}

// The radius ladder's one walk (detail::filter_rungs): each rung adds its annulus to the
// sums of the rung before, so after each rung the output must be the filter at that
// radius (the double reference), with the same members.
TEST(FilterRungs, EachRungIsTheFilterAtItsRadius)
{
    const EstimatorImage est = random_estimators(45, 29, 3, 21);
    const std::vector<int> radii = {1, 2, 4, 9};
    for (bool guided : {false, true}) {
        GuideImages g(45, 29, guided, guided, 8, /*noise=*/guided);
        DenoiseOptions opt;
        opt.radius = 9;
        opt.sigma_spatial = 3.f;
        opt.sigma_albedo = 0.05f;
        opt.sigma_normal = 0.2f;
        for (SimdLevel level : supported_simd_levels()) {
            SCOPED_TRACE(std::string(simd_level_name(level)) + (guided ? " guided" : ""));
            Output fast(est.width, est.height, est.channels);
            std::vector<int> seen;
            detail::filter_rungs(est, g.guides, opt, radii, fast.planes(), fast.diagnostics(), 0,
                                 level, [&](int radius) {
                                     seen.push_back(radius);
                                     DenoiseOptions at = opt;
                                     at.radius = radius;
                                     Output ref(est.width, est.height, est.channels);
                                     filter_reference(est, g.guides, at, ref.planes(),
                                                      ref.diagnostics());
                                     SCOPED_TRACE("radius " + std::to_string(radius));
                                     expect_agree(fast, ref);
                                 });
            EXPECT_EQ(seen, radii);
        }
    }
}

TEST(FilterRungs, BitwiseIdenticalForAnyThreadCountAndRefusesBadRadii)
{
    const EstimatorImage est = random_estimators(150, 97, 3, 5);
    GuideImages g(150, 97, true, true, 6, /*noise=*/true);
    DenoiseOptions opt;
    opt.radius = 12;
    auto rungs_with = [&](int nthreads) {
        Output o(150, 97, 3);
        std::vector<float> all;
        detail::filter_rungs(est, g.guides, opt, {1, 3, 8, 12}, o.planes(), o.diagnostics(),
                             nthreads, SimdLevel::Auto, [&](int) {
                                 all.insert(all.end(), o.values.begin(), o.values.end());
                                 all.insert(all.end(), o.effective.begin(), o.effective.end());
                             });
        return all;
    };
    const std::vector<float> one = rungs_with(1), two = rungs_with(2);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0);
    Output o(150, 97, 3);
    for (const std::vector<int>& bad : {std::vector<int>{3, 2}, {0, 4}, {4, 13}})
        EXPECT_THROW(
            detail::filter_rungs(est, {}, opt, bad, o.planes(), {}, 1, SimdLevel::Auto, [](int) {}),
            std::invalid_argument);
}

TEST(Filter, WritesThroughStridedInterleavedOutput)
{
    const EstimatorImage est = random_estimators(20, 10, 3, 5);
    Output dense(20, 10, 3);
    filter(est, {}, DenoiseOptions{}, dense.planes());
    std::vector<float> rgba(20 * 10 * 4, -7.f);
    std::vector<Plane> interleaved;
    for (int c = 0; c < 3; ++c)
        interleaved.push_back(Plane{rgba.data() + c, 4, 80});
    filter(est, {}, DenoiseOptions{}, interleaved);
    for (int i = 0; i < 200; ++i) {
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(rgba[i * 4 + c], dense.values[c * 200 + i]);
        EXPECT_EQ(rgba[i * 4 + 3], -7.f) << "the fourth channel is not touched";
    }
}

TEST(Filter, RejectsInvalidArguments)
{
    const EstimatorImage est = random_estimators(4, 4, 3, 1);
    Output out(4, 4, 3);
    DenoiseOptions bad;
    bad.radius = -1;
    EXPECT_THROW(filter(est, {}, bad, out.planes()), std::invalid_argument);
    bad = {};
    bad.alpha = 1.0;
    EXPECT_THROW(filter(est, {}, bad, out.planes()), std::invalid_argument);
    bad = {};
    bad.sigma_spatial = 0.f;
    EXPECT_THROW(filter(est, {}, bad, out.planes()), std::invalid_argument);
    std::vector<Plane> too_few = out.planes();
    too_few.pop_back();
    EXPECT_THROW(filter(est, {}, DenoiseOptions{}, too_few), std::invalid_argument);
}

TEST(PixelMask, GrownMaskIsEveryPixelWithASetPixelInItsBox)
{
    // Against the rule written out pixel by pixel, on random sparse masks of odd shapes,
    // for radii 0 (a copy), 1, 2 and wider than the image.
    std::mt19937 rng(5);
    for (const auto& [w, h] : {std::pair{23, 17}, {1, 9}, {40, 3}})
        for (int radius : {0, 1, 2, 50}) {
            PixelMask mask(std::size_t(w) * h);
            for (auto& m : mask)
                m = std::uniform_int_distribution<int>(0, 9)(rng) == 0;
            const PixelMask got = grown_mask(mask, w, h, radius);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    bool any = false;
                    for (int yy = std::max(0, y - radius); yy <= std::min(h - 1, y + radius); ++yy)
                        for (int xx = std::max(0, x - radius); xx <= std::min(w - 1, x + radius);
                             ++xx)
                            any = any || mask[std::size_t(yy) * w + xx];
                    ASSERT_EQ(got[std::size_t(y) * w + x] != 0, any)
                        << w << "x" << h << ", radius " << radius << ", pixel " << x << "," << y;
                }
        }
}

}  // namespace
}  // namespace statmc
