// Russian roulette's survival probabilities, and that ACRR falls back to classic roulette,
// sample for sample, whenever its estimates are unusable.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "renderer_test_support.h"
#include "statmc/render/camera.h"
#include "statmc/render/integrator.h"
#include "statmc/render/russian_roulette.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"

using namespace statmc::render;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

TEST(RussianRoulette, ClassicIsPbrtV3)
{
    EXPECT_FLOAT_EQ(classic_survival(Rgb{0.5f, 0.2f, 0.1f}), 0.5f);
    EXPECT_NEAR(classic_survival(Rgb{0.01f}), 0.01f, 1e-7f);
    EXPECT_FLOAT_EQ(classic_survival(Rgb{0.99f}), 0.95f);  // q never below 0.05 ...
    // ... but pbrt-v3 (rrThreshold 1) rolls no dice at full throughput.
    EXPECT_FLOAT_EQ(classic_survival(Rgb{1.f}), 1.f);
    EXPECT_FLOAT_EQ(classic_survival(Rgb{3.f, 0.1f, 0.1f}), 1.f);
}

TEST(RussianRoulette, AcrrSurvivalFollowsTheApproximateContribution)
{
    // s = max β · L̂_next / L̂_0.
    EXPECT_FLOAT_EQ(*acrr_survival(0.5f, 0.4f, 1.f), 0.2f);
    EXPECT_FLOAT_EQ(*acrr_survival(1.f, 0.9f, 1.f), 0.9f);
    EXPECT_FLOAT_EQ(*acrr_survival(1.f, 0.97f, 1.f), 0.95f);  // q = max(0.05, 1 − s)
    EXPECT_EQ(*acrr_survival(2.f, 1.f, 1.f), 1.f);            // s ≥ 1: no roulette
    // A zero estimate does not kill the path: p stays ≥ kMinSurvival (unbiasedness).
    EXPECT_FLOAT_EQ(*acrr_survival(1.f, 0.f, 1.f), kMinSurvival);
    EXPECT_FLOAT_EQ(*acrr_survival(1e-9f, 1e-9f, 1.f), kMinSurvival);
    for (float beta : {0.f, 1e-6f, 0.3f, 1.f, 10.f})
        for (float next : {0.f, 0.01f, 0.5f, 2.f})
            for (float pixel : {1e-6f, 0.1f, 1.f, 100.f}) {
                const float p = *acrr_survival(beta, next, pixel);
                EXPECT_GT(p, 0.f);
                EXPECT_LE(p, 1.f);
            }
}

TEST(RussianRoulette, AcrrRefusesUnusableEstimates)
{
    EXPECT_FALSE(acrr_survival(0.5f, 0.4f, 0.f));   // L̂_0 = 0: no division by zero
    EXPECT_FALSE(acrr_survival(0.5f, 0.4f, -1.f));  // non-positive
    EXPECT_FALSE(acrr_survival(0.5f, 0.4f, kNaN));
    EXPECT_FALSE(acrr_survival(0.5f, 0.4f, kInf));
    EXPECT_FALSE(acrr_survival(0.5f, kNaN, 1.f));
    EXPECT_FALSE(acrr_survival(0.5f, -0.1f, 1.f));
    EXPECT_FALSE(acrr_survival(0.5f, kInf, 1.f));
    EXPECT_FALSE(acrr_survival(kNaN, 0.4f, 1.f));
}

TEST(RussianRoulette, UnusableEstimatesRenderExactlyAsClassic)
{
    // With ACRR from the first hit on, samples of the test room under estimates that are
    // NaN, L̂_0 = 0 or L̂_0 < 0 must equal classic roulette's bit for bit (same random
    // numbers, same decisions), while usable estimates must change some samples (so
    // that the comparison can fail).
    const auto desc = parse_scene_string(statmc::render::test::test_room(), "room.pbrt");
    const Scene scene(desc);
    const Camera camera(desc.camera, 16, 16);
    IntegratorSettings classic{desc.maxdepth, {}, {}};
    classic.roulette.start_bounce = 0;
    IntegratorSettings acrr = classic;
    acrr.roulette.mode = RouletteMode::Acrr;
    const PathIntegrator plain(scene, classic), steered(scene, acrr);
    const BounceLayout layout{5, 0};
    auto differing = [&](const std::vector<float>& values) {
        return statmc::render::test::differing_samples(plain, steered, camera,
                                                       {values.data(), &layout}, 3);
    };
    EXPECT_EQ(differing({kNaN, kNaN, kNaN, kNaN, kNaN}), 0);
    EXPECT_EQ(differing({0.f, 1.f, 1.f, 1.f, 1.f}), 0);
    EXPECT_EQ(differing({-1.f, 1.f, 1.f, 1.f, 1.f}), 0);
    EXPECT_EQ(differing({1.f, kNaN, kNaN, kNaN, kNaN}), 0);   // every decision falls back
    EXPECT_GT(differing({1.f, 0.5f, 0.4f, 0.3f, 0.2f}), 10);  // ACRR does decide otherwise
}

TEST(RussianRoulette, FirstIterationHasNoEstimatesAndIsClassic)
{
    // The first iteration (4 spp) has no estimates yet: ACRR and SMIS must render it bit
    // for bit as classic roulette and standard MIS do; the second one must differ.
    const auto desc = parse_scene_string(statmc::render::test::test_room(), "room.pbrt");
    IntegratorSettings classic;
    classic.roulette.start_bounce = 0;
    IntegratorSettings steered = classic;
    steered.roulette.mode = RouletteMode::Acrr;
    steered.mis.mode = MisMode::Selective;
    auto means = [&](int spp, const IntegratorSettings& s) {
        return statmc::render::test::render_scene(desc, 16, 16, spp, 9, 0, s)
            .film->stats.planes()
            .mean;
    };
    EXPECT_EQ(means(4, classic), means(4, steered));
    EXPECT_NE(means(8, classic), means(8, steered));
}
