// Selective MIS: which technique is skipped, the weights that keep the estimator
// unbiased, and that unusable win estimates give standard MIS sample for sample.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "renderer_test_support.h"
#include "statmc/render/camera.h"
#include "statmc/render/integrator.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"
#include "statmc/render/selective_mis.h"

using namespace statmc::render;

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}

TEST(SelectiveMis, SkipsOnlyATechniqueThatAlmostNeverWins)
{
    const float t = 0.001f;
    auto both = [](TechniqueChoice c) { return c.light && c.bsdf; };
    EXPECT_TRUE(both(choose_techniques(0.5f, 0.5f, t)));
    EXPECT_TRUE(both(choose_techniques(0.0011f, 0.9989f, t)));  // share 0.0011 ≥ t
    const TechniqueChoice no_light = choose_techniques(0.0009f, 0.9991f, t);
    EXPECT_FALSE(no_light.light);
    EXPECT_TRUE(no_light.bsdf);
    const TechniqueChoice no_bsdf = choose_techniques(3.f, 0.f, t);
    EXPECT_TRUE(no_bsdf.light);
    EXPECT_FALSE(no_bsdf.bsdf);
    // Shares, not absolute rates: a dim pixel whose paths rarely win anything keeps both...
    EXPECT_TRUE(both(choose_techniques(1e-4f, 1e-4f, t)));
    // ...and no estimate, or an unusable one, means standard MIS.
    EXPECT_TRUE(both(choose_techniques(0.f, 0.f, t)));
    EXPECT_TRUE(both(choose_techniques(kNaN, 1.f, t)));
    EXPECT_TRUE(both(choose_techniques(1.f, kNaN, t)));
    EXPECT_TRUE(both(choose_techniques(-0.1f, 1.f, t)));
    EXPECT_TRUE(both(choose_techniques(1.f, std::numeric_limits<float>::infinity(), t)));
}

TEST(SelectiveMis, WeightsSumToOneOverTheTechniquesThatRun)
{
    // An unbiased combination needs w_light + w_bsdf = 1 wherever both densities are
    // positive, counting only the techniques that are sampled.
    for (float pl : {0.1f, 1.f, 30.f})
        for (float pb : {0.2f, 1.f, 5.f}) {
            const TechniqueChoice both, no_light{false, true}, no_bsdf{true, false};
            EXPECT_NEAR(both.light_weight(pl, pb) + both.bsdf_weight(pb, pl), 1.f, 1e-6f);
            EXPECT_EQ(no_light.bsdf_weight(pb, pl), 1.f);
            EXPECT_EQ(no_bsdf.light_weight(pl, pb), 1.f);
            EXPECT_EQ(no_bsdf.bsdf_weight(pb, pl), 0.f);
        }
}

TEST(SelectiveMis, UnusableWinEstimatesRenderExactlyAsStandardMis)
{
    const auto desc = parse_scene_string(statmc::render::test::test_room(), "room.pbrt");
    const Scene scene(desc);
    const Camera camera(desc.camera, 16, 16);
    IntegratorSettings standard{desc.maxdepth, {}, {}};
    IntegratorSettings selective = standard;
    selective.mis.mode = MisMode::Selective;
    const PathIntegrator plain(scene, standard), steered(scene, selective);
    const BounceLayout layout{0, 6};
    auto differing = [&](float light_wins, float bsdf_wins) {
        std::vector<float> values;
        for (int b = 0; b < 6; ++b) {
            values.push_back(light_wins);
            values.push_back(bsdf_wins);
        }
        return statmc::render::test::differing_samples(plain, steered, camera,
                                                       {values.data(), &layout}, 5);
    };
    EXPECT_EQ(differing(kNaN, kNaN), 0);
    EXPECT_EQ(differing(0.f, 0.f), 0);  // nothing won yet
    EXPECT_EQ(differing(-1.f, 2.f), 0);
    EXPECT_EQ(differing(0.5f, 0.5f), 0);  // both win: standard MIS
    EXPECT_GT(differing(1.f, 0.f), 25);   // BSDF skipped: light weight 1
    EXPECT_GT(differing(0.f, 1.f), 25);   // light skipped: no shadow rays
}
