// ACRR and SMIS converge to the same image as classic roulette and standard MIS, and
// adaptive sampling to the same image as uniform sampling: region means of independent
// renders (different seeds) agree in Welch's test.
//
// Bounds. Each render has 1024 spp (Cornell: iterations 4, 4, 8, ..., 512, so ACRR steers
// 8 of 9 iterations) or 2048 spp (Veach MIS); a region averages ≥ 64 pixels, so its mean is normal
// to a very good approximation and z = (m_a − m_b) / sqrt(se_a² + se_b²) (se from the variance
// layers) is standard normal. The bound |z| < 4.5 has a two-sided tail of 6.8e-6 per region and
// channel; over the 48 (Cornell) or 54 (Veach MIS) comparisons of a test the union bound
// gives a false-positive rate ≤ 3.7e-4. Seeds are fixed, so the outcome is in fact
// deterministic. Power: the whole-image standard error of the difference must be below
// 1% (Cornell) or 3% (Veach MIS) of the mean, and a region's is about 4 times (2.5 times)
// that, so a bias of 5–20% confined to one region, or a few percent overall, would fail.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <utility>

#include "renderer_test_support.h"
#include "statmc/render/camera.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"

using namespace statmc::render;
using statmc::render::test::Rendered;

namespace {

constexpr double kZBound = 4.5;

/// Welch's z for every region × channel, and the whole image's relative standard error.
struct Comparison {
    double max_abs_z = 0;
    std::string worst;
    double relative_se = 0;  ///< of the whole-image difference, relative to the mean
    int regions = 0;
};

Comparison welch_regions(const Film& a, const Film& b, int rw, int rh)
{
    const auto pa = a.stats.planes(), pb = b.stats.planes();
    const std::size_t m = std::size_t(pa.width) * pa.height;
    Comparison c;
    auto region = [&](const statmc::StatisticsPlanes& p, int ch, int x0, int y0, int x1, int y1) {
        double mean = 0, var = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const std::size_t i = std::size_t(y) * pa.width + x;
                mean += p.mean[ch * m + i];
                var += p.variance[ch * m + i] / p.count[i];
            }
        const double n = double(x1 - x0) * (y1 - y0);
        return std::pair{mean / n, var / (n * n)};
    };
    for (int ch = 0; ch < 3; ++ch) {
        for (int y0 = 0; y0 + rh <= pa.height; y0 += rh)
            for (int x0 = 0; x0 + rw <= pa.width; x0 += rw) {
                const auto [ma, va] = region(pa, ch, x0, y0, x0 + rw, y0 + rh);
                const auto [mb, vb] = region(pb, ch, x0, y0, x0 + rw, y0 + rh);
                const double z = (ma - mb) / std::sqrt(va + vb);
                ++c.regions;
                if (!(std::abs(z) < c.max_abs_z)) {
                    c.max_abs_z = std::abs(z);
                    std::ostringstream s;
                    s << "region (" << x0 << ", " << y0 << ") channel " << ch << ": " << ma
                      << " vs " << mb << ", z = " << z;
                    c.worst = s.str();
                }
            }
        const auto [ma, va] = region(pa, ch, 0, 0, pa.width, pa.height);
        const auto [mb, vb] = region(pb, ch, 0, 0, pa.width, pa.height);
        c.relative_se = std::max(c.relative_se, std::sqrt(va + vb) / (0.5 * (ma + mb)));
    }
    return c;
}

/// Renders `desc` with `a` and with `b` (independent seeds; `b` adaptively when
/// `b_adaptive` says so) and expects every region to
/// agree (|z| < kZBound) with a whole-image relative standard error below `max_rel_se`.
/// Returns the two renders for the test's own checks.
std::pair<Rendered, Rendered> expect_agreement(const std::string& scene, int w, int h, int spp,
                                               int rw, int rh, const IntegratorSettings& a,
                                               const IntegratorSettings& b, double max_rel_se,
                                               const char* what,
                                               const AdaptiveSettings& b_adaptive = {})
{
    const auto desc = parse_scene_file(scene);
    Rendered ra = statmc::render::test::render_scene(desc, w, h, spp, 21, 0, a);
    Rendered rb = statmc::render::test::render_scene(desc, w, h, spp, 22, 0, b, b_adaptive);
    const Comparison c = welch_regions(*ra.film, *rb.film, rw, rh);
    EXPECT_EQ(c.regions, 3 * (w / rw) * (h / rh));
    EXPECT_LT(c.max_abs_z, kZBound) << c.worst;
    EXPECT_LT(c.relative_se, max_rel_se);
    std::printf("%s: max |z| %.2f over %d, relative se %.4f, rays %.3g vs %.3g\n", what,
                c.max_abs_z, c.regions, c.relative_se, double(rb.rays), double(ra.rays));
    return {std::move(ra), std::move(rb)};
}

}  // namespace

TEST(Unbiased, AcrrAgreesWithClassicRoulette)
{
    const std::string shared = statmc::render::test::shared_dir();
    if (shared.empty())
        GTEST_SKIP() << "../shared/scenes not present";
    IntegratorSettings classic;
    IntegratorSettings acrr;
    acrr.roulette.mode = RouletteMode::Acrr;
    acrr.roulette.start_bounce = 0;  // as in the seed's C.2: roulette from the first hit
    const auto [a, b] = expect_agreement(shared + "/scenes/cornell-box/scene.pbrt", 32, 32, 1024, 8,
                                         8, classic, acrr, 0.01, "ACRR vs classic");
    // ACRR did steer: it traces a clearly different number of rays (deterministic).
    EXPECT_GT(std::abs(double(b.rays) / double(a.rays) - 1), 0.05) << a.rays << " vs " << b.rays;
}

TEST(Unbiased, SelectiveMisAgreesWithStandardMis)
{
    const std::string shared = statmc::render::test::shared_dir();
    if (shared.empty())
        GTEST_SKIP() << "../shared/scenes not present";
    IntegratorSettings standard;
    IntegratorSettings selective;
    selective.mis.mode = MisMode::Selective;
    // Glossy highlights of small lights are noisy: here the power bound is 3%.
    const auto [a, b] = expect_agreement(shared + "/scenes/veach-mis/scene.pbrt", 48, 27, 2048, 8,
                                         9, standard, selective, 0.03, "SMIS vs standard");
    // SMIS did skip a technique at the first hit of a good share of the pixels (what the
    // last iteration's estimates decide; BSDF sampling, mostly, which loses to the
    // lights' cone sampling on the plates).
    const Film& f = *b.film;
    const BounceEstimates est =
        f.steering->denoise(RenderSettings{}.bounce_filter);  // as the render denoised them
    int skipped = 0;
    for (std::size_t i = 0; i < std::size_t(f.width) * f.height; ++i) {
        const PixelEstimates p = est.pixel(i);
        const TechniqueChoice t =
            choose_techniques(p.light_wins(0), p.bsdf_wins(0), selective.mis.threshold);
        skipped += !(t.light && t.bsdf);
    }
    EXPECT_GT(skipped, f.width * f.height / 10) << skipped << " of " << f.width * f.height;
    std::printf("SMIS skipped a technique at %d of %d first hits\n", skipped, f.width * f.height);
}

// Adaptive sampling moves samples between pixels, and each pixel's mean stays its own
// samples' mean. Strictly, a count decided from the pixel's own earlier samples makes that
// mean biased (optional stopping); here the decision comes from the denoised estimate of a
// 3×3 block, where a pixel's own samples weigh little, so the bias should be far below what
// these renders resolve. Same bounds as above (z per region, ≥ 64 pixels each); with
// threshold 0 nothing stops and samples only move, with 0.1 most pixels stop early.
// Each region's standard error comes from its pixels' own variance/count, which is what
// non-uniform counts give.
TEST(Unbiased, AdaptiveSamplingAgreesWithUniformSampling)
{
    const std::string shared = statmc::render::test::shared_dir();
    if (shared.empty())
        GTEST_SKIP() << "../shared/scenes not present";
    for (const double threshold : {0.0, 0.1}) {
        AdaptiveSettings adaptive;
        adaptive.enabled = true;
        adaptive.noise_threshold = threshold;
        const auto [a, b] = expect_agreement(shared + "/scenes/cornell-box/scene.pbrt", 32, 32,
                                             1024, 8, 8, {}, {}, 0.02,
                                             threshold > 0 ? "adaptive (threshold 0.1) vs uniform"
                                                           : "adaptive vs uniform",
                                             adaptive);
        // It did adapt: the counts differ from pixel to pixel by a wide margin.
        const Film::SampleCounts counts = b.film->sample_counts();
        EXPECT_FALSE(counts.uniform);
        EXPECT_GT(counts.max, 4 * counts.min) << counts.min << " .. " << counts.max;
        // With the threshold, pixels did stop: fewer samples than the schedule's in all.
        if (threshold > 0) {
            EXPECT_LT(counts.mean, 0.9 * 1024) << counts.mean;
        }
        std::printf("  counts %d .. %d, mean %.1f\n", counts.min, counts.max, counts.mean);
    }
}
