// Adaptive sampling (docs/sampling.md): the allocation against hand-solved and brute-force
// optima, converged regions that stop while an emitter's edge keeps sampling, agreement
// with uniform sampling in Welch's test, and the operator on non-uniform counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "renderer_test_support.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/render/adaptive_sampling.h"
#include "statmc/render/checkpoint.h"
#include "statmc/render/exr_output.h"
#include "statmc/render/scene_parser.h"

using namespace statmc::render;

namespace {

/// A statistics image whose pixel i holds counts[i] samples (of value 1).
statmc::StatisticsImage<3> image_with_counts(int w, int h, const std::vector<int>& counts)
{
    statmc::StatisticsImage<3> img(w, h);
    const float one[3] = {1, 1, 1};
    for (int i = 0; i < w * h; ++i)
        for (int s = 0; s < counts[std::size_t(i)]; ++s)
            img.add(i % w, i / w, one);
    return img;
}

double objective(const std::vector<float>& r, const std::vector<int>& n,
                 const std::vector<std::uint32_t>& a)
{
    double sum = 0;
    for (std::size_t i = 0; i < r.size(); ++i)
        sum += r[i] / double(n[i] + int(a[i]));
    return sum;
}

/// A camera looking at an emitter that spans x in [−10, right] at depth 1, with nothing
/// beyond: right = 0 fills the left half of the view, and the middle column of an odd width
/// straddles the edge (half its samples see the emitter); right = 10 fills the view. Both
/// sides are exactly constant.
std::string emitter_scene(const std::string& right)
{
    return "LookAt 0 0 0  0 0 -1  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
           "Integrator \"path\" \"integer maxdepth\" 1\nWorldBegin\n"
           "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [1 1 1]\n" +
           statmc::render::test::quad(
               "-10 -10 -1  " + right + " -10 -1  " + right + " 10 -1  -10 10 -1", "0 0 1") +
           "AttributeEnd\nWorldEnd\n";
}

}  // namespace

TEST(AdaptiveSampling, AllocationMatchesTheHandSolvedOptimum)
{
    // n = 16 everywhere, r = 1, 4, 16, 0; spp 8 → budget 32, bounds [2, 64]. The totals
    // n + a = c·sqrt(r) with pixel 0 and 3 at the floor: 2 + 2 + (2c − 16) + (4c − 16) = 32
    // gives c = 10, so a = 2, 4, 24, 2.
    const auto img = image_with_counts(4, 1, {16, 16, 16, 16});
    AdaptiveSettings s;
    s.enabled = true;
    const std::vector<float> r{1.f, 4.f, 16.f, 0.f};
    const SampleAllocation a = allocate_samples({r, r}, img, 8, s);
    EXPECT_EQ(a.counts, (std::vector<std::uint32_t>{2, 4, 24, 2}));
    EXPECT_EQ(a.total, 32u);
    EXPECT_EQ(a.converged, 0u);
}

TEST(AdaptiveSampling, AllocationIsWithinOnePercentOfTheGreedyOptimum)
{
    // Greedy marginal allocation (one sample at a time to the pixel whose Σ r/n falls
    // most, within the bounds) is the exact integer optimum of this separable convex
    // problem; the sqrt rule with carried fractions must come close to it.
    std::mt19937 rng(7);
    const int w = 23, h = 17, spp = 8;
    std::vector<int> n(std::size_t(w * h));
    std::vector<float> r(n.size());
    for (std::size_t i = 0; i < n.size(); ++i) {
        n[i] = 16 + int(rng() % 48);
        r[i] = std::pow(10.f, float(rng() % 4000) / 1000.f - 2.f);  // 0.01 .. 100
    }
    const auto img = image_with_counts(w, h, n);
    AdaptiveSettings s;
    s.enabled = true;
    const SampleAllocation a = allocate_samples({r, r}, img, spp, s);
    const std::uint32_t lo = 2, hi = 64;
    EXPECT_EQ(a.total, std::uint64_t(spp) * n.size());
    EXPECT_EQ(std::accumulate(a.counts.begin(), a.counts.end(), std::uint64_t(0)), a.total);
    for (std::uint32_t c : a.counts) {
        EXPECT_GE(c, lo);
        EXPECT_LE(c, hi);
    }
    std::vector<std::uint32_t> greedy(n.size(), lo);
    for (std::uint64_t left = a.total - lo * n.size(); left > 0; --left) {
        std::size_t best = 0;
        double gain = -1;
        for (std::size_t i = 0; i < n.size(); ++i) {
            if (greedy[i] == hi)
                continue;
            const double m = n[i] + greedy[i];
            const double g = r[i] / m - r[i] / (m + 1);
            if (g > gain) {
                gain = g;
                best = i;
            }
        }
        ++greedy[best];
    }
    const double ours = objective(r, n, a.counts), optimum = objective(r, n, greedy);
    EXPECT_LE(ours, optimum * 1.01) << ours << " vs " << optimum;
    EXPECT_GE(ours, optimum * (1 - 1e-12));
}

TEST(AdaptiveSampling, ConvergedPixelsTakeNothingAndTheBudgetShrinks)
{
    // Threshold 0.1 at n = 16: converged when 1.96·sqrt(r/16) ≤ 0.1, i.e. r ≤ 0.0416, for r
    // of the pixel's own mean; the denoised estimate's r (here larger) only spreads samples.
    const auto img = image_with_counts(3, 1, {16, 16, 8});
    AdaptiveSettings s;
    s.enabled = true;
    s.noise_threshold = 0.1;
    // Pixel 2 is as quiet, but holds fewer samples than min_spp: it may not stop yet.
    const SampleAllocation a = allocate_samples({{0.04f, 0.05f, 0.f}, {1.f, 1.f, 1.f}}, img, 4, s);
    EXPECT_EQ(a.counts[0], 0u);
    EXPECT_EQ(a.converged, 1u);
    EXPECT_EQ(a.total, 8u);  // 4 samples per pixel for the two still sampled
    EXPECT_GE(a.counts[2], 1u);
    EXPECT_EQ(a.counts[1] + a.counts[2], 8u);
}

TEST(AdaptiveSampling, APixelWhoseVarianceOverflowsNeverConverges)
{
    // Samples of 0 and 1e30 (finite, so they count) have a variance beyond float: the pixel
    // and its block are never taken for converged, and the rest stops as it should.
    const int w = 5, h = 3;
    statmc::StatisticsImage<3> img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int s = 0; s < 16; ++s) {
                const float v = (x == 0 && y == 1) ? float(s % 2) * 1e30f : 1.f;
                const float rgb[3] = {v, v, v};
                img.add(x, y, rgb);
            }
    const RelativeVariance r = relative_variance(img, {});
    AdaptiveSettings s;
    s.enabled = true;
    s.noise_threshold = 0.5;
    const SampleAllocation a = allocate_samples(r, img, 4, s);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool near = x <= 1;
            EXPECT_EQ(a.counts[std::size_t(y) * w + x] > 0, near) << x << "," << y;
        }
    // No denoised variance to spread the budget by: each takes the floor rate, one sample.
    EXPECT_EQ(a.total, 6u);
}

TEST(AdaptiveSampling, RelativeVarianceFollowsTheStatisticsAndDilates)
{
    // A constant image (1, no variance) but one pixel with variance: r is 0 away from it,
    // and its 3×3 block shares its value. With mean 10 ± 0.26 the test tells it from 1, so
    // it has no members (g = 1) and both maps hold s² / (10² + 0.01); with mean 1 it joins
    // its neighbours, whose average is 1 and far more precise than its own mean.
    const int w = 9, h = 7;
    for (const float centre_mean : {10.f, 1.f}) {
        statmc::StatisticsImage<3> img(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int s = 0; s < 16; ++s) {
                    const float v =
                        (x == 4 && y == 3) ? centre_mean - 1.f + float(s % 2) * 2.f : 1.f;
                    const float rgb[3] = {v, v, v};
                    img.add(x, y, rgb);
                }
        const RelativeVariance r = relative_variance(img, {});
        const double own = (16.0 / 15.0) / (double(centre_mean) * centre_mean + 0.01);
        EXPECT_NEAR(r.own[3 * w + 4], own, 1e-6 * own) << centre_mean;
        if (centre_mean == 10.f)
            EXPECT_EQ(r.denoised[3 * w + 4], r.own[3 * w + 4]);
        else
            EXPECT_LT(r.denoised[3 * w + 4], r.own[3 * w + 4] / 4);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const bool near = std::abs(x - 4) <= 1 && std::abs(y - 3) <= 1;
                EXPECT_EQ(r.own[i], near ? r.own[3 * w + 4] : 0.f) << x << "," << y;
                EXPECT_EQ(r.denoised[i], near ? r.denoised[3 * w + 4] : 0.f) << x << "," << y;
            }
    }
}

TEST(AdaptiveSampling, ConvergedRegionsStopWhileTheEmitterEdgeKeepsSampling)
{
    const SceneDescription desc = parse_scene_string(emitter_scene("0"), "edge.pbrt");
    AdaptiveSettings s;
    s.enabled = true;
    s.noise_threshold = 0.01;
    const int w = 33, h = 9;
    const auto r = statmc::render::test::render_scene(desc, w, h, 512, 3, 0, {}, s);
    const Film& f = *r.film;
    // Iterations 4, 4, 8 uniform (16 = min_spp), then 16, 32, 64, 128, 256: a pixel that
    // never stops takes at least a quarter of each, 124 more.
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double n = f.stats.at(x, y).n;
            if (x == 16) {
                EXPECT_GE(n, 16 + 124) << "edge pixel " << x << "," << y;
            } else if (x <= 14 || x >= 18) {
                EXPECT_EQ(n, 16) << "flat pixel " << x << "," << y;
            }
        }
    EXPECT_TRUE(r.stats.complete);
    // The edge is half covered: its estimate is unbiased whatever its count.
    const auto& edge = f.stats.at(16, 4);
    EXPECT_NEAR(edge.raw[0].mean, 0.5, 4 * std::sqrt(0.25 / edge.n));
}

TEST(AdaptiveSampling, ARenderWhoseEveryPixelConvergesStopsEarly)
{
    // No edge in view: every pixel is the emitter, constant, converged at min_spp.
    const SceneDescription desc = parse_scene_string(emitter_scene("10"), "emitter.pbrt");
    AdaptiveSettings s;
    s.enabled = true;
    s.noise_threshold = 0.01;
    const auto r = statmc::render::test::render_scene(desc, 5, 4, 256, 1, 0, {}, s);
    EXPECT_TRUE(r.stats.converged);
    EXPECT_TRUE(r.stats.complete);
    EXPECT_EQ(r.stats.samples, 16u * 20u);
    EXPECT_EQ(r.film->sample_counts().max, 16);
}

TEST(AdaptiveSampling, TheDenoiseOperatorReadsEachPixelsOwnCount)
{
    // An adaptive render's file, denoised by the operator (the paper's filter, no guides),
    // equals core's filter on the film's own statistics, per-pixel counts and all; the same
    // statistics with every count set to the mean give a different image, so the test
    // would see an operator that took statmc:sppMean for every pixel.
    const SceneDescription desc =
        parse_scene_string(statmc::render::test::test_room(), "room.pbrt");
    AdaptiveSettings s;
    s.enabled = true;
    const int w = 24, h = 16;
    const auto r = statmc::render::test::render_scene(desc, w, h, 64, 5, 0, {}, s);
    const Film& f = *r.film;
    OutputInfo info;
    info.spp = f.sample_counts();
    ASSERT_FALSE(info.spp.uniform);
    const OIIO::ImageBuf image = make_output_image(f, info);
    statmc::DenoiseImageOptions options = statmc::DenoiseImageOptions::paper();
    options.guides.albedo = options.guides.normal = statmc::GuideUse::Off;
    OIIO::ImageBuf denoised;
    ASSERT_TRUE(statmc::denoise(denoised, image, options)) << denoised.geterror();

    auto core_filter = [&](statmc::StatisticsPlanes planes) {
        const statmc::EstimatorImage est =
            statmc::estimators_from_statistics(planes.view(), statmc::TestDomain::BoxCox);
        const std::size_t n = std::size_t(w) * h;
        std::vector<float> out(3 * n);
        std::vector<statmc::Plane> planes_out;
        for (int c = 0; c < 3; ++c)
            planes_out.push_back(statmc::dense_plane(out.data() + c * n, w));
        statmc::filter(est, {}, statmc::DenoiseOptions::paper(), planes_out);
        return out;
    };
    const statmc::StatisticsPlanes own = f.stats.planes();
    statmc::StatisticsPlanes flat = own;
    std::fill(flat.count.begin(), flat.count.end(), float(info.spp.mean));
    const std::vector<float> expected = core_filter(own), with_mean = core_filter(flat);
    const std::size_t n = std::size_t(w) * h;
    int differ_from_mean = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                float rgb[3];
                denoised.getpixel(x, y, rgb, 3);
                const std::size_t i = c * n + std::size_t(y) * w + x;
                EXPECT_EQ(rgb[c], expected[i]) << x << "," << y << " channel " << c;
                differ_from_mean += with_mean[i] != expected[i];
            }
    EXPECT_GT(differ_from_mean, int(n) / 10);
}

TEST(AdaptiveSampling, AStoppedRenderResumesFromItsCheckpointBitwiseEqual)
{
    // Stopped after its fifth iteration (two of them adaptive), saved through the checkpoint
    // file and resumed into a fresh film: the allocations depend only on the film, and each
    // pixel's stream carries on from its own count, so the result is the straight render's.
    const SceneDescription desc =
        parse_scene_string(statmc::render::test::test_room(), "room.pbrt");
    AdaptiveSettings s;
    s.enabled = true;
    s.noise_threshold = 0.02;
    const int w = 24, h = 16;
    const auto straight = statmc::render::test::render_scene(desc, w, h, 256, 9, 0, {}, s);

    statmc::render::test::ScratchDir dir("adaptive");
    const std::string path = dir.file("o.exr.checkpoint");
    const CheckpointIdentity identity{"room.pbrt", 0, 9, w, h, 0, 1, 0, 256, s.text()};
    Scene scene(desc);
    const Camera camera(desc.camera, w, h);
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    rs.schedule = schedule_for_spp(256);
    rs.seed = 9;
    rs.integrator.maxdepth = desc.maxdepth;
    rs.adaptive = s;
    rs.checkpoint_seconds = 1e-9;  // a checkpoint at every iteration boundary
    std::atomic<bool> cancel{false};
    {
        Film film(w, h);
        const RenderStats stopped = render(
            scene, camera, rs, film, &cancel,
            [&](int iteration, const Film&, const IterationStats&) { cancel = iteration == 4; },
            [&](const Film& f, std::uint64_t done) {
                write_checkpoint(path, f, identity, {done, 0});
            });
        ASSERT_TRUE(stopped.interrupted);
        ASSERT_FALSE(stopped.complete);
    }
    Film resumed(w, h);
    rs.samples_done = read_checkpoint(path, resumed, identity).samples_done;
    EXPECT_EQ(rs.samples_done, 64u);  // iterations 4, 4, 8, 16, 32
    ASSERT_FALSE(resumed.sample_counts().uniform);
    cancel = false;
    const RenderStats rest = render(scene, camera, rs, resumed, &cancel);
    EXPECT_TRUE(rest.complete);
    const auto& a = straight.film->stats.accumulators();
    const auto& b = resumed.stats.accumulators();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].n, b[i].n) << "pixel " << i;
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(a[i].raw[c].mean, b[i].raw[c].mean) << "pixel " << i;
            ASSERT_EQ(a[i].raw[c].m2, b[i].raw[c].m2) << "pixel " << i;
        }
    }
}
