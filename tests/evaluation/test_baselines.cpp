// The evaluation's baselines (bench/evaluation/baselines): what each must do for the comparison
// with statmc to mean anything.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "baselines/baselines.h"

namespace statmc {
namespace {

constexpr int kW = 48, kH = 32;

struct Frame {
    std::vector<float> mean = std::vector<float>(3 * kW * kH),
                       variance = std::vector<float>(3 * kW * kH),
                       out = std::vector<float>(3 * kW * kH),
                       albedo = std::vector<float>(3 * kW * kH),
                       normal = std::vector<float>(3 * kW * kH, 0.5f);
    std::array<ConstPlane, 3> m, v;
    std::array<Plane, 3> o;
    Guides guides;

    // Left half 0.2, right half 0.8 (in the image and in the albedo); noise of std `sigma`.
    explicit Frame(float sigma)
    {
        std::mt19937_64 rng(3);
        std::normal_distribution<float> noise(0.f, 1.f);
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const std::size_t i = std::size_t(c) * kW * kH + std::size_t(y) * kW + x;
                    mean[i] = truth(x) + sigma * noise(rng);
                    variance[i] = sigma * sigma;
                    albedo[i] = truth(x);
                }
        for (int c = 0; c < 3; ++c) {
            m[c] = dense_plane(mean.data() + c * kW * kH, kW);
            v[c] = dense_plane(variance.data() + c * kW * kH, kW);
            o[c] = dense_plane(out.data() + c * kW * kH, kW);
            guides.albedo[c] = dense_plane(albedo.data() + c * kW * kH, kW);
            guides.normal[c] = dense_plane(normal.data() + c * kW * kH, kW);
        }
    }
    static float truth(int x) { return x < kW / 2 ? 0.2f : 0.8f; }
    double mse(const std::vector<float>& img) const
    {
        double s = 0;
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const double d =
                        img[std::size_t(c) * kW * kH + std::size_t(y) * kW + x] - truth(x);
                    s += d * d;
                }
        return s / (3.0 * kW * kH);
    }
};

TEST(Baselines, NlmLeavesANoiseFreeImageAlone)
{
    Frame f(0.f);
    baselines::nlm(f.m, f.v, kW, kH, {}, f.o);
    EXPECT_LT(f.mse(f.out), 1e-12);
}

TEST(Baselines, NlmDenoisesWithoutCrossingTheEdge)
{
    // σ = 0.05 against a step of 0.6 (12 σ): patches across the step are far apart.
    Frame f(0.05f);
    baselines::nlm(f.m, f.v, kW, kH, {}, f.o);
    EXPECT_LT(f.mse(f.out), f.mse(f.mean) / 5);
}

TEST(Baselines, CrossBilateralFollowsTheAlbedoEdge)
{
    Frame f(0.05f);
    baselines::cross_bilateral(f.m, f.guides, kW, kH, {}, f.o);
    EXPECT_LT(f.mse(f.out), f.mse(f.mean) / 20);
    // Next to the edge, the other side's albedo differs by 6 σ_a: no bleeding.
    for (int y = 0; y < kH; ++y)
        EXPECT_NEAR(f.out[std::size_t(y) * kW + kW / 2 - 1], 0.2f, 0.02f);
}

}  // namespace
}  // namespace statmc
