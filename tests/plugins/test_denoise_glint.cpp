// A glint amid dark neighbours (docs/method.md §5, "The mutual guard"): a few bright hits
// among misses, which the t-test at few samples cannot tell from the dark pixels around
// it. Where its value rests on two samples' worth or more, the default keeps its light;
// no neighbour is brightened or darkened beyond 3 standard errors of its own truth. A
// caustic-like region's error falls with every doubling of the sample count, and where the
// energy check acts on one at an ROI's edge, the ROI still gets the full run's pixels.
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include "statmc/core/statistics_image.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/passes/passes.h"

namespace statmc {
namespace {

constexpr int kW = 33, kH = 33, kGx = 16, kGy = 16;
constexpr float kHit = 30.f, kP = 0.3f;  // the glint's expectation: 9

float dark_truth(int c) { return 0.02f * (1.f + 0.2f * c); }

// One sample of pixel (x, y): the glint hits kHit (less 10% per channel) with probability
// kP; the field is exponential with mean dark_truth.
void sample(std::mt19937_64& rng, int x, int y, float* s)
{
    if (x == kGx && y == kGy) {
        const bool hit = std::uniform_real_distribution<float>(0, 1)(rng) < kP;
        for (int c = 0; c < 3; ++c)
            s[c] = hit ? kHit * (1.f - 0.1f * c) : 0.f;
        return;
    }
    const float e = std::exponential_distribution<float>(1.f)(rng);
    for (int c = 0; c < 3; ++c)
        s[c] = dark_truth(c) * e;
}

// The effective count (Σx)²/Σx² of the glint's red values: what it rests on.
struct Glint {
    double sum = 0, squares = 0;
    void add(double v)
    {
        sum += v;
        squares += v * v;
    }
    double support() const { return squares > 0 ? sum * sum / squares : 0; }
};

// Statistics of n samples per pixel.
OIIO::ImageBuf full_statistics(int n, std::uint64_t seed, Glint& glint)
{
    std::mt19937_64 rng(seed);
    StatisticsImage<3> img(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int i = 0; i < n; ++i) {
                float s[3];
                sample(rng, x, y, s);
                img.add(x, y, s);
                if (x == kGx && y == kGy)
                    glint.add(s[0]);
            }
    return layers::make_statistics_image(img.planes());
}

// K renders of 4 samples per pixel with the channels `names`, `width` × kH, through
// --passes: each render is one sample. `draw` writes one sample of pixel (x, y), a value per
// channel.
using SampleDraw = std::function<void(std::mt19937_64&, int x, int y, float* sample)>;
OIIO::ImageBuf through_passes(int K, std::uint64_t seed, const std::vector<std::string>& names,
                              const SampleDraw& draw, Glint& glint, int width = kW)
{
    std::mt19937_64 rng(seed);
    const int n = int(names.size());
    std::vector<OIIO::ImageBuf> renders;
    for (int k = 0; k < K; ++k) {
        OIIO::ImageSpec spec(width, kH, n, OIIO::TypeFloat);
        spec.channelnames = names;
        OIIO::ImageBuf r(spec);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < width; ++x) {
                std::vector<float> px(n, 0.f), s(n);
                for (int i = 0; i < 4; ++i) {
                    draw(rng, x, y, s.data());
                    for (int c = 0; c < n; ++c)
                        px[c] += s[c] / 4;
                }
                r.setpixel(x, y, px.data());
                if (x == kGx && y == kGy)
                    glint.add(px[0]);
            }
        renders.push_back(r);
    }
    std::vector<const OIIO::ImageBuf*> pointers;
    for (const OIIO::ImageBuf& r : renders)
        pointers.push_back(&r);
    return passes(pointers);
}

OIIO::ImageBuf k_passes(int K, std::uint64_t seed, Glint& glint)
{
    return through_passes(K, seed, {"R", "G", "B"}, sample, glint);
}

// What 20 seeds of a route gave: the glint's output over its noisy mean, summed over the
// runs where its value rests on two samples' worth or more, and how many those were.
struct GlintRuns {
    int supported = 0, kept = 0;
    double energy = 0;  // Σ out / Σ noisy at the glint over the supported runs
};

// Runs 20 seeds; in every run every 8-neighbour must end within 3 standard errors
// (σ/√samples) of its truth: the glint's light neither leaks into them nor darkens them.
GlintRuns check_runs(const std::string& route, int samples,
                     const std::function<OIIO::ImageBuf(std::uint64_t, Glint&)>& make)
{
    const DenoiseImageOptions defaults;
    GlintRuns runs;
    double out_sum = 0, in_sum = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        Glint glint;
        const OIIO::ImageBuf in = make(seed, glint);
        const OIIO::ImageBuf out = denoise(in, defaults);
        EXPECT_FALSE(out.has_error()) << out.geterror();
        if (glint.support() >= 2) {
            ++runs.supported;
            runs.kept += out.getchannel(kGx, kGy, 0, 0) == in.getchannel(kGx, kGy, 0, 0);
            out_sum += out.getchannel(kGx, kGy, 0, 0);
            in_sum += in.getchannel(kGx, kGy, 0, 0);
        }
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                for (int c = 0; c < 3; ++c)
                    if (dx || dy) {
                        const float se = dark_truth(c) / std::sqrt(float(samples));
                        EXPECT_NEAR(out.getchannel(kGx + dx, kGy + dy, 0, c), dark_truth(c), 3 * se)
                            << route << ", seed " << seed << ", neighbour (" << dx << ", " << dy
                            << "), channel " << c;
                    }
    }
    runs.energy = in_sum > 0 ? out_sum / in_sum : 0;
    EXPECT_GT(runs.supported, 0) << route << ": no run had a glint of two samples' worth";
    return runs;
}

TEST(Glint, KeepsItsLightWhereItRestsOnSeveralSamplesAndLeavesItsNeighbours)
{
    // Where the glint's hits are few (n = 4) it may still be averaged away: 55% of its light
    // was kept there when this was written. From n = 8 and K = 8 the mutual guard keeps it
    // (93-100% measured); at n = 64 and K = 16, in every run. K = 4 passes (df = 6) is left
    // out: there the guard's variance ratio cannot tell the glint from its neighbours, and
    // its light spreads into them (up to 1.1 against a truth of 0.02): the open part of
    // the promise, docs/research-log.md.
    for (int n : {4, 8, 16, 64}) {
        const GlintRuns runs =
            check_runs("n = " + std::to_string(n), n,
                       [&](std::uint64_t seed, Glint& g) { return full_statistics(n, seed, g); });
        if (n >= 8) {
            EXPECT_GT(runs.energy, 0.9) << "n = " << n;
        }
        if (n >= 64) {
            EXPECT_EQ(runs.kept, runs.supported) << "n = " << n;
        }
    }
    for (int K : {8, 16}) {
        const GlintRuns runs =
            check_runs("K = " + std::to_string(K), 4 * K,
                       [&](std::uint64_t seed, Glint& g) { return k_passes(K, seed, g); });
        EXPECT_GT(runs.energy, 0.9) << "K = " << K;
        if (K >= 16) {
            EXPECT_EQ(runs.kept, runs.supported) << "K = " << K;
        }
    }
}

// A glint seen through a glossy bounce (docs/method.md §5, guide noise): its albedo guide
// is whatever each sample's reflection hit (0 or 0.4), so its guides are noisy, while the
// dark surface around it has a clean albedo of 0.25. Its hits are rare (one sample of 80 in
// about 30), so its value rests on about one sample and the mutual guard does not keep it.
OIIO::ImageBuf reflected_glint(int K, std::uint64_t seed, Glint& glint)
{
    auto draw = [](std::mt19937_64& rng, int x, int y, float* s) {
        const bool at_glint = x == kGx && y == kGy;
        std::uniform_real_distribution<float> u(0, 1);
        const float e = std::exponential_distribution<float>(1.f)(rng);
        const bool hit = u(rng) < 0.03f, bright_reflection = u(rng) < 0.5f;
        for (int c = 0; c < 3; ++c) {
            s[c] = at_glint ? (hit ? 80.f : 0.f) : dark_truth(c) * e;
            s[3 + c] = at_glint ? (bright_reflection ? 0.4f : 0.f) : 0.25f;
        }
    };
    return through_passes(K, seed, {"R", "G", "B", "albedo.R", "albedo.G", "albedo.B"}, draw,
                          glint);
}

// The guide-noise correction takes out the less noisy side's noise: between the glint and
// neighbours with clean guides that is none, so the glint's own noise buys it no neighbour
// that does not take it. Every output, the glint's included, is then to the bit what it is
// with the guides' variances left out. (With the one-sided correction, u_i + min(u_i, u_j),
// the glint took its dark neighbours in: 2.31 instead of 2.50 at seed 1.)
TEST(Glint, SeenThroughAGlossyBounceItsGuideNoiseBuysItNoNeighbours)
{
    const DenoiseImageOptions defaults;
    int hit_runs = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        Glint glint;
        const OIIO::ImageBuf in = reflected_glint(8, seed, glint);
        const int variance = in.spec().channelindex("albedoVariance.Y");
        ASSERT_GE(variance, 0) << "the guides' noise is measured";
        std::vector<int> others;
        for (int c = 0; c < in.nchannels(); ++c)
            if (c != variance)
                others.push_back(c);
        const OIIO::ImageBuf without = OIIO::ImageBufAlgo::channels(in, int(others.size()), others);
        const OIIO::ImageBuf a = denoise(in, defaults), b = denoise(without, defaults);
        ASSERT_FALSE(a.has_error()) << a.geterror();
        ASSERT_FALSE(b.has_error()) << b.geterror();
        hit_runs += glint.sum > 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(a.getchannel(x, y, 0, c), b.getchannel(x, y, 0, c))
                        << "seed " << seed << ", pixel (" << x << ", " << y << "), channel " << c;
    }
    EXPECT_GE(hit_runs, 3) << "too few runs where the glint was hit";
}

}  // namespace
}  // namespace statmc

namespace statmc {
namespace {

// A caustic-like patch (samples 0 or 1/p, expectation 1) on a dark exponential field.
OIIO::ImageBuf caustic(int n, std::uint64_t seed, float p)
{
    std::mt19937_64 rng(seed);
    StatisticsImage<3> img(32, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            for (int i = 0; i < n; ++i) {
                float s[3];
                const bool patch = x >= 10 && x < 22 && y >= 10 && y < 22;
                const bool hit = std::uniform_real_distribution<float>(0, 1)(rng) < p;
                const float e = std::exponential_distribution<float>(1.f)(rng);
                for (int c = 0; c < 3; ++c)
                    s[c] = patch ? (hit ? 1.f / p : 0.f) : 0.02f * e;
                img.add(x, y, s);
            }
    return layers::make_statistics_image(img.planes());
}

double caustic_mse(const OIIO::ImageBuf& image)
{
    double sum = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const bool patch = x >= 10 && x < 22 && y >= 10 && y < 22;
            for (int c = 0; c < 3; ++c)
                sum += std::pow(image.getchannel(x, y, 0, c) - (patch ? 1.0 : 0.02), 2);
        }
    return sum / (32 * 32 * 3);
}

TEST(Consistency, ACausticPatchsErrorFallsWithEveryDoublingOfTheSamples)
{
    // Hits of 20 with probability 0.05 (mean 1) in a 12×12 patch, mean over three seeds.
    // With rarer hits (p = 0.01) the default's error still rises from 16 to 64 samples:
    // docs/research-log.md, the open part of the promise.
    const DenoiseImageOptions defaults;
    double previous = 1e30;
    for (int n = 4; n <= 1024; n *= 2) {
        double error = 0;
        for (std::uint64_t seed : {1u, 2u, 3u})
            error += caustic_mse(denoise(caustic(n, seed, 0.05f), defaults)) / 3;
        EXPECT_LT(error, previous) << "n = " << n;
        previous = error;
    }
}

// A caustic through 4 passes of 4 samples (hits of 20 with p = 0.05 in a patch across the
// ROI's left edge), where the check that `off` turns off changes pixels near that edge: a
// run over the ROI must read the filter's halo and the checks' reach beyond it, and give
// the full run's bits. A small radius and a frame twice the ROI's width, so that the halo
// does not cover the frame.
void expect_roi_gets_full_runs_pixels(const std::function<void(DenoiseImageOptions&)>& off)
{
    constexpr int kWide = 64, kEdge = 32;
    DenoiseImageOptions o;
    o.filter.radius = 3;
    DenoiseImageOptions unchecked = o;
    off(unchecked);
    Glint unused;
    const OIIO::ImageBuf in = through_passes(
        4, 4, {"R", "G", "B"},
        [](std::mt19937_64& rng, int x, int y, float* s) {
            const bool patch = x >= kEdge - 6 && x < kEdge + 6 && y >= 10 && y < 22;
            const float e = std::exponential_distribution<float>(1.f)(rng);
            const bool hit = std::uniform_real_distribution<float>(0, 1)(rng) < 0.05f;
            for (int c = 0; c < 3; ++c)
                s[c] = patch ? (hit ? 20.f : 0.f) : 0.02f * e;
        },
        unused, kWide);
    const OIIO::ImageBuf full = denoise(in, o), plain = denoise(in, unchecked);
    ASSERT_FALSE(full.has_error()) << full.geterror();
    const OIIO::ROI roi(kEdge, kWide, 0, kH);
    int changed_near_edge = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = kEdge; x < kEdge + 6; ++x)
            changed_near_edge += full.getchannel(x, y, 0, 0) != plain.getchannel(x, y, 0, 0);
    EXPECT_GT(changed_near_edge, 0) << "the check must act inside the ROI, near its edge";
    OIIO::ImageBuf part;
    ASSERT_TRUE(denoise(part, in, o, roi)) << part.geterror();
    for (int y = roi.ybegin; y < roi.yend; ++y)
        for (int x = roi.xbegin; x < roi.xend; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(part.getchannel(x, y, 0, c), full.getchannel(x, y, 0, c))
                    << "channel " << c << " at (" << x << ", " << y << ")";
}

TEST(EnergyCheck, AnRoiGetsTheFullRunsPixelsWhereTheCheckActsAtItsEdge)
{
    // The default's energy check (docs/method.md §16).
    expect_roi_gets_full_runs_pixels(
        [](DenoiseImageOptions& o) { o.stages.ladder.energy.radius = 0; });
}

TEST(ResidualCheck, AnRoiGetsTheFullRunsPixelsWhereTheCheckActsAtItsEdge)
{
    // The default's residual check (§17), which reads the energy check's output.
    expect_roi_gets_full_runs_pixels(
        [](DenoiseImageOptions& o) { o.stages.ladder.residual.radius = 0; });
}

}  // namespace
}  // namespace statmc
