// Moderated variances on synthetic statistics whose true variances are known: they must
// lift the variances that few samples underestimate, keep another expectation's variance
// out of a pixel's prior, and give the same bits for any thread count and SIMD level.
#include <cmath>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "same_bits.h"
#include "statmc/core/statistics_image.h"
#include "statmc/core/variance_filter.h"
#include "variance_filter_layout.h"

namespace statmc {
namespace {

using test::same_bits;

constexpr int kW = 48, kH = 32, kSpp = 8;

// Left half: exponential samples of mean 0.2; right half: mean 3.
double mean_at(int x) { return x < kW / 2 ? 0.2 : 3.0; }

StatisticsPlanes synthetic(std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    StatisticsImage<1> img(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            std::exponential_distribution<float> e(float(1 / mean_at(x)));
            for (int s = 0; s < kSpp; ++s) {
                const float v = e(rng);
                img.add(x, y, &v);
            }
        }
    return img.planes();
}

// A dark field (normal samples, mean 0.04, σ = 0.01) beside a bright one of another
// expectation (mean 10, σ = 10), 64 samples per pixel, kDarkW × kDarkH pixels.
constexpr int kDarkW = 24, kDarkH = 12;
StatisticsPlanes dark_beside_bright(std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> dark(0.04f, 0.01f), bright(10.f, 10.f);
    StatisticsImage<1> img(kDarkW, kDarkH);
    for (int y = 0; y < kDarkH; ++y)
        for (int x = 0; x < kDarkW; ++x)
            for (int s = 0; s < 64; ++s) {
                const float v = x < kDarkW / 2 ? dark(rng) : bright(rng);
                img.add(x, y, &v);
            }
    return img.planes();
}

// The dark pixels within 3 of the edge: `lifted` takes the bright side's s² of about 100
// into their prior (10⁴ times their own), `kept` does not (s² of 64 normal samples is
// within ±18%, one sd, of σ², and the prior averages many of them).
void expect_the_edge(const std::vector<float>& lifted, const std::vector<float>& kept)
{
    const double truth = 0.01 * 0.01;
    for (int y = 0; y < kDarkH; ++y)
        for (int x = kDarkW / 2 - 3; x < kDarkW / 2; ++x) {
            const std::size_t i = std::size_t(y) * kDarkW + x;
            EXPECT_GT(lifted[i], 100 * truth) << x << "," << y;
            EXPECT_NEAR(kept[i], truth, 0.5 * truth) << x << "," << y;
        }
}

TEST(VarianceFilter, AnAlbedoGuideAlongAnEdgeKeepsTheOtherSidesVarianceOutOfThePrior)
{
    // The guide weights of the mean filter apply to the prior too: with every neighbour
    // in it (no test on the means), an albedo step where the variance steps keeps the
    // bright side's s² out of the dark side's prior.
    const StatisticsPlanes stats = dark_beside_bright(29);
    std::vector<float> albedo(std::size_t(kDarkW) * kDarkH);
    for (std::size_t i = 0; i < albedo.size(); ++i)
        albedo[i] = int(i % kDarkW) < kDarkW / 2 ? 0.2f : 0.8f;
    Guides guides;
    guides.albedo = {dense_plane(albedo.data(), kDarkW), dense_plane(albedo.data(), kDarkW),
                     dense_plane(albedo.data(), kDarkW)};
    VarianceFilterOptions o;
    o.prior_dof = 16;
    expect_the_edge(denoise_variances(stats.view(), TestDomain::Untransformed, {}, o),
                    denoise_variances(stats.view(), TestDomain::Untransformed, guides, o));
}

TEST(VarianceFilter, SameBitsForAnyThreadCount)
{
    const StatisticsPlanes stats = synthetic(2);
    VarianceFilterOptions o;
    o.prior_dof = 16;
    o.prior_alpha = 0.05;
    const std::vector<float> one = denoise_variances(stats.view(), TestDomain::BoxCox, {}, o, 1);
    EXPECT_EQ(one, denoise_variances(stats.view(), TestDomain::BoxCox, {}, o, 2));
    EXPECT_EQ(one, denoise_variances(stats.view(), TestDomain::BoxCox, {}, o, 0));
}

TEST(VarianceFilter, APixelKeepsItsOwnAndOnlyBorrowersAverage)
{
    StatisticsPlanes stats = synthetic(3);
    const std::size_t borrower = 10 * kW + 10;
    stats.count[borrower] = 3;  // no estimate of its own below 4 samples
    VarianceFilterOptions o;
    const std::vector<float> kept = denoise_variances(stats.view(), TestDomain::BoxCox, {}, o);
    EXPECT_EQ(kept, stats.bc_variance);  // no borrowing, no moderation: every s² as it was
    o.borrow_without_interval = true;
    const std::vector<float> out = denoise_variances(stats.view(), TestDomain::BoxCox, {}, o);
    // Every pixel with an estimate keeps its own s², bit for bit (no moderation here).
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (i != borrower) {
            ASSERT_EQ(out[i], stats.bc_variance[i]) << i;
        }
    }
    // The borrower takes the spatially weighted mean of its disk's s² (radius 3, σ = 2; its
    // neighbours all have estimates), computed here independently.
    double sum = 0, weight = 0;
    for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx)
            if (dx * dx + dy * dy <= 9 && (dx || dy)) {
                const double w = std::exp(-(dx * dx + dy * dy) / 8.0);
                sum += w * stats.bc_variance[(10 + dy) * kW + 10 + dx];
                weight += w;
            }
    EXPECT_NEAR(out[borrower], sum / weight, 1e-6 * sum / weight);
}

// Four samples of a pixel that reaches a light one time in four (else a dark 0.001·U):
// about 0.75⁴ = 32% of the pixels saw no light and claim a variance ~10⁵ below the truth
// p(1 − p) = 0.1875 (the dark speckles of docs/method.md §10); the moderation towards the
// neighbourhood's variance lifts them.
StatisticsPlanes rare_light(std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution hit(0.25);
    std::uniform_real_distribution<float> dark(0.f, 0.001f);
    StatisticsImage<1> img(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int s = 0; s < 4; ++s) {
                const float v = hit(rng) ? 1.f : dark(rng);
                img.add(x, y, &v);
            }
    return img.planes();
}

double share_below(const std::vector<float>& variance, double bound)
{
    std::size_t below = 0;
    for (float v : variance)
        below += v < bound;
    return double(below) / variance.size();
}

TEST(VarianceFilter, ModerationLiftsVariancesThatFewSamplesUnderestimate)
{
    const StatisticsPlanes stats = rare_light(5);
    const double truth = 0.25 * 0.75, bound = truth / 100;
    VarianceFilterOptions own;
    const std::vector<float> plain =
        denoise_variances(stats.view(), TestDomain::Untransformed, {}, own);
    // The failure the moderation is for: expected share 0.32 (binomial sd 0.012 over 1536).
    EXPECT_GT(share_below(plain, bound), 0.25);
    VarianceFilterOptions moderated = own;
    moderated.prior_dof = 4;
    const std::vector<float> lifted =
        denoise_variances(stats.view(), TestDomain::Untransformed, {}, moderated);
    // d₀ = 4 against n − 1 = 3 own degrees of freedom: at least 4/7 of the neighbourhood's
    // mean, which a speckle-free disk of 29 pixels keeps near the truth. The chance that a
    // disk's pooled mean falls below 1/57 of p(1 − p) is far below 1e-9.
    EXPECT_EQ(share_below(lifted, bound), 0.0);
    // Not a replacement: where the pixel's own estimate is sound it still counts 3/7.
    double log_error_plain = 0, log_error_lifted = 0;
    for (std::size_t i = 0; i < lifted.size(); ++i) {
        log_error_plain += std::pow(std::log(plain[i] / truth), 2);
        log_error_lifted += std::pow(std::log(lifted[i] / truth), 2);
    }
    EXPECT_LT(log_error_lifted, log_error_plain / 10);
    // Deterministic for any thread count.
    EXPECT_EQ(lifted, denoise_variances(stats.view(), TestDomain::Untransformed, {}, moderated, 1));
    // The test on the means keeps the lifting: a neighbour that met the light differs from
    // a dark pixel by about one standard error of its own (one hit in 4: t = 1), not more.
    VarianceFilterOptions means_tested = moderated;
    means_tested.prior_alpha = 0.05;
    EXPECT_EQ(
        share_below(denoise_variances(stats.view(), TestDomain::Untransformed, {}, means_tested),
                    bound),
        0.0);
    means_tested.prior_alpha = 1;
    EXPECT_THROW(denoise_variances(stats.view(), TestDomain::Untransformed, {}, means_tested),
                 std::invalid_argument);
    moderated.prior_dof = -1;
    EXPECT_THROW(denoise_variances(stats.view(), TestDomain::Untransformed, {}, moderated),
                 std::invalid_argument);
}

TEST(VarianceFilter, TheMeansTestKeepsAnotherExpectationsVarianceOutOfThePrior)
{
    // With the test on the means, a bright pixel would have to come within 2 of its own
    // standard errors of 0.04 (an 8σ event) to lend a dark pixel its variance.
    const StatisticsPlanes stats = dark_beside_bright(23);
    VarianceFilterOptions o;
    o.prior_dof = 16;
    const std::vector<float> untested =
        denoise_variances(stats.view(), TestDomain::Untransformed, {}, o);
    o.prior_alpha = 0.05;
    expect_the_edge(untested, denoise_variances(stats.view(), TestDomain::Untransformed, {}, o));
}

TEST(VarianceFilter, EverySimdLevelGivesTheScalarLoopsBits)
{
    // Three channels, both guides, pixels without an estimate (n < 4), an infinite and a
    // NaN variance, both ways of treating such pixels, with and without the moderation: the SIMD
    // kernels add the same double products in the same order as the scalar loop, so the floats must
    // be equal, not close. 53 columns leave a ragged tail after the 8- and 4-lane chunks.
    constexpr int w = 53, h = 21;
    std::mt19937_64 rng(17);
    std::exponential_distribution<float> e(1.f);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    StatisticsImage<3> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < 6; ++s) {
                const float v[3] = {e(rng) * (x < w / 2 ? 0.3f : 2.f), e(rng), u(rng)};
                img.add(x, y, v);
            }
    StatisticsPlanes stats = img.planes();
    const std::size_t n = std::size_t(w) * h;
    for (int x : {5, 20, 33})
        stats.count[9 * w + x] = 3;  // no estimate of its own
    stats.variance[0 * n + 10 * w + 12] = INFINITY;
    stats.variance[1 * n + 11 * w + 30] = NAN;
    std::vector<float> albedo(3 * n), normal(3 * n);
    for (float& a : albedo)
        a = u(rng) < 0.5f ? 0.2f : 0.21f;
    for (float& v : normal)
        v = u(rng);
    Guides guides;
    for (int k = 0; k < 3; ++k) {
        guides.albedo[k] = dense_plane(albedo.data() + k * n, w);
        guides.normal[k] = dense_plane(normal.data() + k * n, w);
    }
    for (const Guides& g : {Guides{}, guides})
        for (const bool borrow : {false, true})
            for (const auto& [prior_dof, prior_alpha] :
                 {std::pair{0.0, 0.0}, std::pair{0.0, 0.05}, std::pair{16.0, 0.0},
                  std::pair{16.0, 0.05}}) {
                VarianceFilterOptions o;
                o.borrow_without_interval = borrow;
                o.prior_dof = prior_dof;
                o.prior_alpha = prior_alpha;
                const std::vector<float> scalar = denoise_variances(
                    stats.view(), TestDomain::Untransformed, g, o, 2, SimdLevel::Scalar);
                for (SimdLevel level : supported_simd_levels())
                    EXPECT_TRUE(
                        same_bits(scalar, denoise_variances(stats.view(), TestDomain::Untransformed,
                                                            g, o, 2, level)))
                        << simd_level_name(level) << " guides " << g.has_albedo() << " borrow "
                        << borrow << " d0 " << prior_dof << " prior alpha " << prior_alpha;
                // The prior's test on the means belongs to the moderation: without it
                // (d0 = 0) its level changes nothing (it once read planes never filled).
                if (prior_dof == 0 && prior_alpha > 0) {
                    o.prior_alpha = 0;
                    EXPECT_TRUE(
                        same_bits(scalar, denoise_variances(stats.view(), TestDomain::Untransformed,
                                                            g, o, 2, SimdLevel::Scalar)));
                }
            }
}

TEST(VarianceFilter, TheGuideWeightsShortcutsAreStdExpsOwnAnswers)
{
    // guide_weight skips std::exp at 0 and beyond 746; the filter's bits rest on those
    // being exactly what the call would give, here on this C library.
    const double spatial = 0.8824969025845955;
    for (double e : {0.0, -0.0, 1e-300, 0.5, 700.0, 745.0, 745.13, 745.14, 745.2, 746.0,
                     746.0000001, 800.0, 1e300, double(INFINITY)}) {
        const double called = spatial * std::exp(-e), shortcut = detail::guide_weight(spatial, e);
        EXPECT_EQ(std::memcmp(&called, &shortcut, sizeof called), 0) << "exponent " << e;
    }
    EXPECT_TRUE(std::isnan(detail::guide_weight(spatial, NAN)));
}

TEST(VarianceFilter, RefusesBadOptionsAndMissingPlanes)
{
    StatisticsPlanes stats = synthetic(4);
    VarianceFilterOptions bad;
    bad.radius = 0;
    EXPECT_THROW(denoise_variances(stats.view(), TestDomain::BoxCox, {}, bad),
                 std::invalid_argument);
    // Neither fourth moment is read.
    stats.bc_moment4.clear();
    stats.moment3.clear();
    stats.moment4.clear();
    EXPECT_NO_THROW(denoise_variances(stats.view(), TestDomain::BoxCox));
    EXPECT_NO_THROW(denoise_variances(stats.view(), TestDomain::Untransformed));
    stats.bc_variance.clear();
    EXPECT_THROW(denoise_variances(stats.view(), TestDomain::BoxCox), std::invalid_argument);
}

}  // namespace
}  // namespace statmc
