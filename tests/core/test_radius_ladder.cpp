// The radius ladder (docs/method.md §11): each pixel at the largest radius whose interval
// still agrees with those of the smaller ones. A firefly that the paper's filter spreads
// into a disk leaves no halo, and a flat field is still denoised.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/method.h"
#include "statmc/core/radius_ladder.h"
#include "statmc/core/statistics_image.h"
#include "statmc/core/variance_filter.h"

namespace statmc {
namespace {

constexpr int kSize = 48, kFx = 24, kFy = 24, kSpp = 16;
constexpr float kTruth = 0.5f, kSigma = 0.1f;  // normal samples; a firefly of 2000× the truth

// What pixel (kFx, kFy) holds as its sample s instead of a normal draw (none: the draw).
using CentreSample = std::function<std::optional<float>(int s)>;

// A flat field of `spp` normal samples per pixel, pixel (kFx, kFy)'s as `centre` says.
StatisticsPlanes flat_field(std::uint64_t seed, int spp, const CentreSample& centre = {})
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<float> noise(kTruth, kSigma);
    StatisticsImage<1> img(kSize, kSize);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int s = 0; s < spp; ++s) {
                const std::optional<float> own =
                    centre && x == kFx && y == kFy ? centre(s) : std::nullopt;
                const float v = own ? *own : noise(rng);
                img.add(x, y, &v);
            }
    return img.planes();
}

// Pixel (kFx, kFy)'s first sample is 2000× the truth.
StatisticsPlanes flat_field_with_firefly(std::uint64_t seed)
{
    return flat_field(seed, kSpp, [](int s) {
        return s == 0 ? std::optional<float>(2000 * kTruth) : std::nullopt;
    });
}

std::vector<float> papers_filter(const StatisticsPlanes& stats)
{
    const EstimatorImage est = estimators_from_statistics(stats.view(), TestDomain::BoxCox);
    std::vector<float> out(est.value.size());
    filter(est, {}, DenoiseOptions::paper(), {dense_plane(out.data(), kSize)});
    return out;
}

// Pixels outside the firefly's 3×3 whose |out − x̄| exceeds `limit` true standard errors σ/√n.
int departures_beyond(const std::vector<float>& out, const StatisticsPlanes& stats, double limit)
{
    const double se = kSigma / std::sqrt(double(kSpp));
    int count = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            if (std::abs(x - kFx) > 1 || std::abs(y - kFy) > 1) {
                const std::size_t i = std::size_t(y) * kSize + x;
                count += std::abs(double(out[i]) - stats.mean[i]) > limit * se;
            }
    return count;
}

RadiusLadderOptions at_z3()
{
    RadiusLadderOptions ladder;
    ladder.alpha = 0.0026997960632601866;  // z = 3
    return ladder;
}

// The default method's ladder: α = 0.005 on variances moderated with d₀ = 16.
RadiusLadderOptions the_defaults_ladder() { return method_settings(Method::Default).stages.ladder; }

std::vector<float> laddered(const StatisticsPlanes& stats,
                            const DenoiseOptions& filter_options = DenoiseOptions::paper(),
                            const RadiusLadderOptions& ladder = at_z3())
{
    const EstimatorImage est = estimators_from_statistics(stats.view(), TestDomain::BoxCox);
    std::vector<float> out(est.value.size());
    filter_with_radius_ladder(stats.view(), est, {}, filter_options,
                              {dense_plane(out.data(), kSize)}, ladder);
    return out;
}

double squared_error(const std::vector<float>& values)
{
    double sum = 0;
    for (float v : values)
        sum += std::pow(v - kTruth, 2);
    return sum;
}

TEST(RadiusLadder, DropsTheFireflysHaloInsteadOfClampingIt)
{
    const StatisticsPlanes stats = flat_field_with_firefly(1);
    const std::vector<float> out = laddered(stats);
    EXPECT_GT(departures_beyond(papers_filter(stats), stats, 3), 100);
    // Even a perfect filter (out = μ) leaves |μ − x̄| > 3 standard errors at 0.27% of the
    // 48² − 9 pixels: 6.2 on average; 17 is that plus 4.5 binomial standard deviations.
    EXPECT_LE(departures_beyond(out, stats, 3), 17);
}

TEST(RadiusLadder, StillDenoisesAFlatField)
{
    // Without the firefly every rung agrees, so pixels climb to large radii: the error
    // against the truth must fall far below the noisy input's.
    const StatisticsPlanes stats = flat_field(3, kSpp);
    const double noisy = squared_error(stats.mean), filtered = squared_error(laddered(stats));
    // Radius 20 averages hundreds of pixels; a 10× lower squared error is a loose floor.
    EXPECT_LT(filtered, noisy / 10) << "noisy " << noisy << " filtered " << filtered;
}

TEST(RadiusLadder, TheDefaultLeavesNoHaloAndStillDenoises)
{
    // Target 5 for the default itself (α = 0.005, z = 2.81, moderated variances, the
    // firefly guard on): no pixel outside the firefly's 3×3 moves by more than 3 standard
    // errors beyond what chance gives a perfect filter (the bound of the test above).
    const StatisticsPlanes stats = flat_field_with_firefly(1);
    EXPECT_LE(departures_beyond(laddered(stats, DenoiseOptions{}, the_defaults_ladder()), stats, 3),
              17);
    const StatisticsPlanes flat = flat_field(3, kSpp);
    const double noisy = squared_error(flat.mean),
                 filtered = squared_error(laddered(flat, DenoiseOptions{}, the_defaults_ladder()));
    EXPECT_LT(filtered, noisy / 10) << "noisy " << noisy << " filtered " << filtered;
}

// A flat field in which pixel (kFx, kFy) holds samples of `value` ± 1e-4: a variance
// thousands of times below its neighbours', which the variance filter (§10's test) does
// not pool with theirs, so its own intervals are nearly points.
StatisticsPlanes flat_field_with_steady_pixel(std::uint64_t seed, float value)
{
    return flat_field(seed, kSpp, [value](int s) {
        return std::optional<float>(value + (s % 2 ? 1e-4f : -1e-4f));
    });
}

RadiusLadderOptions unmoderated(bool overrule)
{
    RadiusLadderOptions ladder = at_z3();
    ladder.variance.prior_dof = 0;  // the pixel's own zero variance stands
    ladder.overrule_lone_stops = overrule;
    return ladder;
}

TEST(RadiusLadder, ALoneStopWhereEveryNeighbourGoesOnIsOverruled)
{
    // The pixel is 0.3σ off the truth with a tiny variance estimate (its samples happened
    // to agree): by its own intervals it stops at rung 0. Its
    // neighbours in the flat field all go on, and so, overruled, does it: it takes their
    // large radius and ends far nearer the truth.
    const float off = kTruth + 0.3f * kSigma;
    const StatisticsPlanes stats = flat_field_with_steady_pixel(5, off);
    const std::size_t p = std::size_t(kFy) * kSize + kFx;
    const std::vector<float> own = laddered(stats, DenoiseOptions::paper(), unmoderated(false));
    const std::vector<float> overruled =
        laddered(stats, DenoiseOptions::paper(), unmoderated(true));
    EXPECT_EQ(own[p], stats.mean[p]);
    EXPECT_LT(std::abs(overruled[p] - kTruth), 0.2 * std::abs(off - kTruth))
        << "overruled " << overruled[p] << ", its own " << stats.mean[p];
    // Everywhere else the field still denoises as before.
    EXPECT_LT(squared_error(overruled), squared_error(stats.mean) / 10);
}

TEST(RadiusLadder, ALonePixelOfItsOwnIsNotAveragedAway)
{
    // A one-pixel feature (a glint of 5× the field) stops by its intervals too, and its
    // neighbours go on; overruled, it climbs the ladder, but the membership test refuses
    // it every neighbour, so every rung is its own value.
    const StatisticsPlanes stats = flat_field_with_steady_pixel(5, 5 * kTruth);
    const std::size_t p = std::size_t(kFy) * kSize + kFx;
    EXPECT_EQ(laddered(stats, DenoiseOptions::paper(), unmoderated(true))[p], stats.mean[p]);
    EXPECT_EQ(laddered(stats, DenoiseOptions{}, the_defaults_ladder())[p], stats.mean[p]);
}

// An image where the ladder stops often: an edge between two levels, heavy-tailed
// (exponential) samples, few of them, and a size that is no multiple of a SIMD width.
StatisticsPlanes edge_with_heavy_tails(int w, int h, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::exponential_distribution<float> unit(1.f);
    StatisticsImage<1> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < 8; ++s) {
                const float v = (2 * x + y < w ? 0.5f : 2.f) * unit(rng);
                img.add(x, y, &v);
            }
    return img.planes();
}

// The wanted pixels of `mask` out of the ladder (or, `ladder` null, the plain filter) with
// and without the mask: the first must be the second's bits.
void expect_masked_bits(const StatisticsPlanes& stats, int w, const PixelMask& mask,
                        const DenoiseOptions& options, const RadiusLadderOptions* ladder)
{
    const EstimatorImage est = estimators_from_statistics(stats.view(), TestDomain::BoxCox);
    auto run = [&](const PixelMask& wanted) {
        std::vector<float> out(est.value.size(), -1.f);
        const std::vector<Plane> planes = {dense_plane(out.data(), w)};
        if (ladder)
            filter_with_radius_ladder(stats.view(), est, {}, options, planes, *ladder, 0, wanted);
        else
            filter(est, {}, options, planes, {}, 0, SimdLevel::Auto, wanted);
        return out;
    };
    const std::vector<float> full = run({}), masked = run(mask);
    int compared = 0, moved = 0;
    for (std::size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) {
            ASSERT_EQ(masked[i], full[i])
                << "pixel " << i % w << "," << i / w << (ladder ? " (ladder)" : " (filter)");
            ++compared;
            moved += full[i] != stats.mean[i];
        }
    EXPECT_GT(moved, compared / 2);  // the pixels compared were denoised
}

TEST(RadiusLadder, AMaskedLadderGivesTheWantedPixelsTheFullLaddersBits)
{
    // An edge, heavy tails, few samples and a size no SIMD width divides: scattered
    // pixels, both corners and a whole row, through the default's ladder and the filter.
    constexpr int w = 61, h = 37;
    const StatisticsPlanes edge = edge_with_heavy_tails(w, h, 7);
    std::mt19937_64 rng(8);
    std::bernoulli_distribution pick(0.03);
    PixelMask wanted(std::size_t(w) * h, 0);
    for (auto& v : wanted)
        v = pick(rng);
    wanted.front() = wanted.back() = 1;
    std::fill(wanted.begin() + 20 * w, wanted.begin() + 21 * w, 1);
    const RadiusLadderOptions ladder = the_defaults_ladder();
    expect_masked_bits(edge, w, wanted, DenoiseOptions{}, &ladder);
    // One pixel by the edge, and a residual check that acts in about half the windows, so
    // that what it reads around the pixel (the energy check's output, within both checks'
    // reach) matters and lies inside the frame.
    RadiusLadderOptions eager = ladder;
    eager.residual.alpha = 0.9;
    PixelMask one(wanted.size(), 0);
    one[std::size_t(h / 2) * w + w / 2] = 1;
    expect_masked_bits(edge, w, one, DenoiseOptions{}, &eager);
    expect_masked_bits(edge, w, wanted, DenoiseOptions{}, nullptr);
    // The moderated variances the intervals read, likewise.
    const std::vector<float> all = denoise_variances(edge.view(), TestDomain::Untransformed, {},
                                                     ladder.variance),
                             some = denoise_variances(edge.view(), TestDomain::Untransformed, {},
                                                      ladder.variance, 0, SimdLevel::Auto, wanted);
    for (std::size_t i = 0; i < wanted.size(); ++i)
        if (wanted[i]) {
            ASSERT_EQ(some[i], all[i]) << "variance at " << i % w << "," << i / w;
        }
    const EstimatorImage est = estimators_from_statistics(edge.view(), TestDomain::BoxCox);
    std::vector<float> out(est.value.size());
    EXPECT_THROW(filter_with_radius_ladder(edge.view(), est, {}, DenoiseOptions{},
                                           {dense_plane(out.data(), w)}, ladder, 0,
                                           PixelMask(10, 1)),
                 std::invalid_argument);
}

// A view of `planes` whose planes interleave, pixel by pixel, in `storage`: the layout an
// EXR's layers have in memory.
StatisticsView interleaved(const StatisticsPlanes& planes, std::vector<float>& storage)
{
    StatisticsView view = planes.view();
    std::vector<ConstPlane*> all = {&view.count};
    for (int c = 0; c < view.channels; ++c)
        for (ConstPlane* p : {&view.mean[c], &view.variance[c], &view.bc_mean[c],
                              &view.bc_variance[c], &view.bc_moment3[c]})
            if (*p)
                all.push_back(p);
    const std::ptrdiff_t k = std::ptrdiff_t(all.size()), w = view.width;
    storage.assign(std::size_t(k) * w * view.height, 0.f);
    for (std::ptrdiff_t j = 0; j < k; ++j) {
        for (int y = 0; y < view.height; ++y)
            for (int x = 0; x < view.width; ++x)
                storage[std::size_t((y * w + x) * k + j)] = (*all[std::size_t(j)])(x, y);
        *all[std::size_t(j)] = ConstPlane{storage.data() + j, k, k * w};
    }
    return view;
}

TEST(RadiusLadder, ItsChecksGiveWhatTheyGiveOnTheImagesOwnInterleavedPlanes)
{
    // The ladder hands its energy and residual checks dense copies of the planes they
    // read. On statistics whose planes interleave, that must be the ladder without the
    // checks followed by the checks on the interleaved planes, bit for bit; three channels
    // of different levels, and a width that is no multiple of the box sums' blocks.
    const int w = 45, h = 31;
    std::mt19937_64 rng(17);
    std::exponential_distribution<float> unit(1.f);
    StatisticsImage<3> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < 8; ++s) {
                const float level = 2 * x + y < w ? 0.5f : 2.f;
                const float v[3] = {level * unit(rng), 2 * level * unit(rng), unit(rng)};
                img.add(x, y, v);
            }
    const StatisticsPlanes stats = img.planes();
    std::vector<float> storage;
    const StatisticsView view = interleaved(stats, storage);
    const EstimatorImage est = estimators_from_statistics(view, TestDomain::BoxCox);
    const DenoiseOptions options = method_settings(Method::Default).filter;
    auto run = [&](const RadiusLadderOptions& ladder, std::vector<float>& out) {
        out.assign(std::size_t(3) * w * h, 0.f);
        std::vector<Plane> planes;
        for (int c = 0; c < 3; ++c)
            planes.push_back(dense_plane(out.data() + std::size_t(c) * w * h, w));
        filter_with_radius_ladder(view, est, {}, options, planes, ladder);
        return planes;
    };
    const RadiusLadderOptions with = the_defaults_ladder();
    RadiusLadderOptions without = with;
    without.energy.radius = without.residual.radius = 0;
    std::vector<float> checked, expected;
    run(with, checked);
    const std::vector<Plane> planes = run(without, expected);
    const std::vector<float> unchecked = expected;
    const std::size_t off = keep_window_energy(view, planes, with.energy) +
                            keep_window_residual(view, planes, with.residual);
    ASSERT_GT(off, 0u);  // the checks acted
    ASSERT_NE(expected, unchecked);
    for (std::size_t i = 0; i < expected.size(); ++i)
        ASSERT_EQ(checked[i], expected[i]) << "at " << i;
}

TEST(RadiusLadder, AMaskedLoneStopIsStillOverruledByTheNeighboursItDoesNotWant)
{
    // Steady pixels (ALoneStopWhereEveryNeighbourGoesOnIsOverruled) on a grid, the mask
    // wanting them alone: each is overruled only because its unwanted neighbours go on, so
    // the ladder must still walk and judge those.
    StatisticsImage<1> img(kSize, kSize);
    std::mt19937_64 rng(9);
    std::normal_distribution<float> noise(kTruth, kSigma);
    PixelMask steady(std::size_t(kSize) * kSize, 0);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool own = x % 6 == 3 && y % 6 == 3;
            steady[std::size_t(y) * kSize + x] = own;
            for (int s = 0; s < kSpp; ++s) {
                const float v =
                    own ? kTruth + 0.3f * kSigma + (s % 2 ? 1e-4f : -1e-4f) : noise(rng);
                img.add(x, y, &v);
            }
        }
    const RadiusLadderOptions overruling = unmoderated(true);
    expect_masked_bits(img.planes(), kSize, steady, DenoiseOptions::paper(), &overruling);
}

}  // namespace
}  // namespace statmc
