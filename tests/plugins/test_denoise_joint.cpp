// Joint AOV denoising (docs/method.md §14): AOVs averaged with the beauty's members and
// weights still sum to the denoised beauty, to float rounding; denoised apart they do not.
#include <algorithm>
#include <cmath>
#include <string>

#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>

#include "statmc/denoise/denoise.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"
#include "test_images.h"

namespace statmc {
namespace {

using test::channel_value;

constexpr int kW = 26, kH = 18;

// Diffuse and specular AOVs with their own noise, and a beauty that is their sum: the
// float sum of the means, the sum of the variances, the shared count.
OIIO::ImageBuf aov_image()
{
    const StatisticsPlanes diffuse = test::variance_aov(test::noisy_statistics(kW, kH, 8, 21));
    const StatisticsPlanes specular = test::variance_aov(test::noisy_statistics(kW, kH, 8, 22));
    StatisticsPlanes beauty = diffuse;
    for (std::size_t i = 0; i < beauty.mean.size(); ++i) {
        beauty.mean[i] = diffuse.mean[i] + specular.mean[i];
        beauty.variance[i] = diffuse.variance[i] + specular.variance[i];
    }
    return layers::make_statistics_image(
        beauty.view(), {}, test::make_guides(kW, kH, 4).planes(),
        {{"diffuse", diffuse.view()}, {"specular", specular.view()}});
}

// aov_image() with specular's mean alone, as the Cycles route gives light groups: joint
// AOVs then share the beauty's test.
OIIO::ImageBuf lead_only_image()
{
    const OIIO::ImageBuf full = aov_image();
    std::vector<int> keep;
    for (int c = 0; c < full.spec().nchannels; ++c)
        if (full.spec().channelnames[c].rfind("specular.variance", 0) != 0)
            keep.push_back(c);
    return OIIO::ImageBufAlgo::channels(full, int(keep.size()), keep);
}

DenoiseImageOptions joint_options(bool joint)
{
    DenoiseImageOptions opt;
    opt.filter.radius = 5;
    opt.aovs = {"diffuse", "specular"};
    opt.joint = joint;
    return opt;
}

// The largest |diffuse + specular − beauty| over the image, relative to the terms' size.
double worst_sum_mismatch(const OIIO::ImageBuf& out)
{
    double worst = 0;
    for (const char* c : {"R", "G", "B"})
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const double d = channel_value(out, std::string("diffuse.") + c, x, y);
                const double s = channel_value(out, std::string("specular.") + c, x, y);
                const double b = channel_value(out, c, x, y);
                worst = std::max(worst, std::abs(d + s - b) / (std::abs(d) + std::abs(s) + 1e-3));
            }
    return worst;
}

TEST(DenoiseJoint, JointAovsSumToTheDenoisedBeauty)
{
    const OIIO::ImageBuf in = aov_image();
    // Every AOV's test deciding: the beauty shares their one membership.
    const OIIO::ImageBuf all = denoise(in, joint_options(true));
    ASSERT_FALSE(all.has_error()) << all.geterror();
    // A few float roundings of each term: the input's own sum is rounded once too.
    EXPECT_LT(worst_sum_mismatch(all), 1e-6);
    // So with the beauty's test alone deciding.
    const OIIO::ImageBuf joint = denoise(lead_only_image(), joint_options(true));
    ASSERT_FALSE(joint.has_error()) << joint.geterror();
    EXPECT_LT(worst_sum_mismatch(joint), 1e-6);
    // Denoised apart, each by its own test, they drift apart by far more.
    const OIIO::ImageBuf apart = denoise(in, joint_options(false));
    ASSERT_FALSE(apart.has_error()) << apart.geterror();
    EXPECT_GT(worst_sum_mismatch(apart), 1e-3);
    // And the AOVs did move.
    EXPECT_NE(channel_value(joint, "diffuse.G", 7, 5), channel_value(in, "diffuse.G", 7, 5));
    EXPECT_NE(channel_value(all, "diffuse.G", 7, 5), channel_value(in, "diffuse.G", 7, 5));
}

TEST(DenoiseJoint, TheBeautyIsTheClassicFilterWithTheContextAndEachAovKeepsItsStatistics)
{
    const OIIO::ImageBuf in = lead_only_image();
    const OIIO::ImageBuf joint = denoise(in, joint_options(true));
    DenoiseImageOptions classic = DenoiseImageOptions::classic();
    classic.filter.radius = 5;
    classic.stages.context_radius = DenoiseImageOptions{}.stages.context_radius;  // shared
    const OIIO::ImageBuf beauty = denoise(in, classic);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            ASSERT_TRUE(
                test::same_bits(channel_value(joint, "R", x, y), channel_value(beauty, "R", x, y)));
            ASSERT_TRUE(test::same_bits(channel_value(joint, "diffuse.variance.B", x, y),
                                        channel_value(in, "diffuse.variance.B", x, y)));
        }
    EXPECT_NE(joint.spec().get_string_attribute(layers::attr::kDenoiseSkipped).find("joint AOVs"),
              std::string::npos);
}

TEST(DenoiseJoint, SeparateAovsEqualOneRunPerAov)
{
    const OIIO::ImageBuf in = aov_image();
    const OIIO::ImageBuf apart = denoise(in, joint_options(false));
    DenoiseImageOptions one;
    one.filter.radius = 5;
    one.aov = "specular";
    const OIIO::ImageBuf specular = denoise(in, one);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            ASSERT_TRUE(test::same_bits(channel_value(apart, "specular.G", x, y),
                                        channel_value(specular, "specular.G", x, y)));
}

TEST(DenoiseJoint, WhatCannotBeJointIsRefused)
{
    DenoiseImageOptions opt = joint_options(true);
    opt.aovs.clear();
    EXPECT_NE(opt.validate().find("joint needs the AOVs"), std::string::npos);
    opt = joint_options(true);
    opt.temporal.frames = 1;
    EXPECT_NE(opt.validate().find("joint cannot be combined yet with temporal"), std::string::npos);
    opt = joint_options(true);
    opt.aovs.push_back("diffuse");
    EXPECT_EQ(opt.validate(), "aovs lists 'diffuse' twice");

    const OIIO::ImageBuf in = aov_image();
    opt = joint_options(true);
    opt.aovs = {"diffuse", "emission"};
    const OIIO::ImageBuf out = denoise(in, opt);
    ASSERT_TRUE(out.has_error());
    EXPECT_NE(out.geterror().find("missing layer emission (channels emission.R"), std::string::npos)
        << out.geterror();
}

// Every AOV with its statistics: a neighbour joins only where the beauty's and each AOV's
// tests accept it. Every added test can only remove members, so the beauty keeps at most
// the members of its own test and comes out nearer its noisy input wherever the AOVs' tests
// disagree. (The context test, which the side-by-side test leaves out, is left out of the
// comparison too.)
TEST(DenoiseJoint, EveryAovsTestDecidesWhenEachHasItsStatistics)
{
    const OIIO::ImageBuf in = aov_image();
    const OIIO::ImageBuf all = denoise(in, joint_options(true));
    DenoiseImageOptions lead_options = joint_options(true);
    lead_options.stages.context_radius = 0;
    // The beauty's own test: the beauty's statistics are the same in both images.
    const OIIO::ImageBuf lead = denoise(lead_only_image(), lead_options);
    ASSERT_FALSE(all.has_error()) << all.geterror();
    ASSERT_FALSE(lead.has_error()) << lead.geterror();
    int moved = 0;
    double towards_input = 0, total = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float a = channel_value(all, "G", x, y), l = channel_value(lead, "G", x, y);
            const float noisy = channel_value(in, "G", x, y);
            moved += a != l;
            towards_input += std::abs(a - noisy);
            total += std::abs(l - noisy);
        }
    EXPECT_GT(moved, kW * kH / 10);
    EXPECT_LT(towards_input, total);
    EXPECT_EQ(all.spec().get_string_attribute(layers::attr::kDenoiseSkipped).find("own tests"),
              std::string::npos);
}

TEST(DenoiseJoint, AnAovWithoutStatisticsSharesTheLeadsTestAndSaysSo)
{
    const OIIO::ImageBuf in = lead_only_image();
    ASSERT_FALSE(in.has_error()) << in.geterror();
    const OIIO::ImageBuf joint = denoise(in, joint_options(true));
    ASSERT_FALSE(joint.has_error()) << joint.geterror();
    EXPECT_NE(joint.spec()
                  .get_string_attribute(layers::attr::kDenoiseSkipped)
                  .find("AOV specular has no variance of its own"),
              std::string::npos);
}

TEST(DenoiseJoint, MoreAovsThanTheFilterTakesSideBySideShareTheLeadsTestAndSaySo)
{
    // Four RGB AOVs with their statistics and an RGB beauty: 15 channels side by side,
    // beyond the filter's 12. The lead's test decides, and the sums still hold.
    const StatisticsPlanes a = test::variance_aov(test::noisy_statistics(kW, kH, 8, 31));
    const StatisticsPlanes b = test::variance_aov(test::noisy_statistics(kW, kH, 8, 32));
    StatisticsPlanes beauty = a;
    for (std::size_t i = 0; i < beauty.mean.size(); ++i) {
        beauty.mean[i] = 2 * (a.mean[i] + b.mean[i]);
        beauty.variance[i] = 2 * (a.variance[i] + b.variance[i]);
    }
    const OIIO::ImageBuf in = layers::make_statistics_image(
        beauty.view(), {}, {},
        {{"a1", a.view()}, {"b1", b.view()}, {"a2", a.view()}, {"b2", b.view()}});
    DenoiseImageOptions opt;
    opt.filter.radius = 5;
    opt.aovs = {"a1", "b1", "a2", "b2"};
    opt.joint = true;
    const OIIO::ImageBuf out = denoise(in, opt);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_NE(out.spec()
                  .get_string_attribute(layers::attr::kDenoiseSkipped)
                  .find("15 channels side by side"),
              std::string::npos)
        << out.spec().get_string_attribute(layers::attr::kDenoiseSkipped);
    double worst = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            double sum = 0;
            for (const char* aov : {"a1.G", "b1.G", "a2.G", "b2.G"})
                sum += channel_value(out, aov, x, y);
            const double b = channel_value(out, "G", x, y);
            worst = std::max(worst, std::abs(sum - b) / (std::abs(sum) + 1e-3));
        }
    EXPECT_LT(worst, 1e-5);
}

}  // namespace
}  // namespace statmc
