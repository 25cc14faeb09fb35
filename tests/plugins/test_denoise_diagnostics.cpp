// denoise with diagnostics: the per-pixel member count and effective sample count, on
// images whose membership is known without running the filter.
#include <cmath>

#include <gtest/gtest.h>

#include "statmc/denoise/denoise.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"
#include "test_images.h"

namespace statmc {
namespace {

using test::channel_value;

constexpr int kW = 15, kH = 11, kRadius = 3;

// Sample counts that differ from pixel to pixel, so that the effective count is not
// just members × n.
float count_at(int x, int y) { return float(4 + (x + 2 * y) % 3); }

// A noise-free image (variance 0): `left` on columns x < split, `right` from split on.
// Equal means always pass the test; means 0.7 apart never do.
OIIO::ImageBuf noise_free(float left, float right, int split, const std::string& aov = "")
{
    StatisticsPlanes s;
    s.width = kW;
    s.height = kH;
    s.channels = 3;
    const std::size_t n = std::size_t(kW) * kH;
    s.count.resize(n);
    s.mean.resize(3 * n);
    s.variance.assign(3 * n, 0.f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const std::size_t i = std::size_t(y) * kW + x;
            s.count[i] = count_at(x, y);
            for (int c = 0; c < 3; ++c)
                s.mean[c * n + i] = x < split ? left : right;
        }
    layers::StatisticsMetadata meta;
    meta.aov = aov;
    return layers::make_statistics_image(s, meta);
}

DenoiseImageOptions diagnostic_options(float sigma_s)
{
    DenoiseImageOptions o;
    o.filter.radius = kRadius;
    o.filter.sigma_spatial = sigma_s;
    o.guides.albedo = o.guides.normal = GuideUse::Off;
    o.diagnostics = true;
    o.stages.context_radius = 0;  // the members counted here are those of the pixels' own test
    return o;
}

// What the filter must find at (x, y) when the members are exactly the disk taps inside
// the image on the same side of `split`: their number and (Σw)² / Σ w²/n_j with the
// spatial Gaussian w = exp(−d²/2σ²), computed here in double.
struct Expected {
    double members = 0, effective = 0;
};

Expected expected_at(int x, int y, int split, double sigma_s)
{
    double members = 0, wsum = 0, inverse = 0;
    for (int dy = -kRadius; dy <= kRadius; ++dy)
        for (int dx = -kRadius; dx <= kRadius; ++dx) {
            const int xj = x + dx, yj = y + dy;
            if (dx * dx + dy * dy > kRadius * kRadius || xj < 0 || yj < 0 || xj >= kW || yj >= kH ||
                (xj < split) != (x < split))
                continue;
            const double w = std::exp(-(dx * dx + dy * dy) / (2 * sigma_s * sigma_s));
            members += 1;
            wsum += w;
            inverse += w * w / count_at(xj, yj);
        }
    return {members, wsum * wsum / inverse};
}

void expect_diagnostics(const OIIO::ImageBuf& out, int split, double sigma_s,
                        const std::string& aov = "")
{
    const std::string members = layers::diagnostics_channel(aov, layers::kMembersChannel);
    const std::string effective =
        layers::diagnostics_channel(aov, layers::kEffectiveSamplesChannel);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const Expected e = expected_at(x, y, split, sigma_s);
            ASSERT_EQ(channel_value(out, members, x, y), float(e.members))
                << "(" << x << ", " << y << ")";
            ASSERT_NEAR(channel_value(out, effective, x, y), e.effective, 1e-5 * e.effective)
                << "(" << x << ", " << y << ")";
        }
}

TEST(DenoiseDiagnostics, FlatRegionCountsEveryDiskTapClampedAtBorders)
{
    const OIIO::ImageBuf out = denoise(noise_free(0.5f, 0.5f, kW), diagnostic_options(2.f));
    ASSERT_FALSE(out.has_error()) << out.geterror();
    expect_diagnostics(out, kW, 2.0);
    // Spot checks against counts by hand: the 29-tap disk of r = 3 in the middle, the
    // quarter disk with its axes (11 taps) in a corner.
    EXPECT_EQ(channel_value(out, "diagnostics.members", 7, 5), 29.f);
    EXPECT_EQ(channel_value(out, "diagnostics.members", 0, 0), 11.f);
}

TEST(DenoiseDiagnostics, EqualWeightsGiveMembersTimesTheHarmonicMeanCount)
{
    // σ_s far beyond the radius makes every weight 1: the plain average of M means of
    // variance σ²/n_j has variance σ² Σ(1/n_j) / M², so N = M² / Σ 1/n_j.
    const OIIO::ImageBuf out = denoise(noise_free(0.5f, 0.5f, kW), diagnostic_options(1e4f));
    ASSERT_FALSE(out.has_error()) << out.geterror();
    double members = 0, inverse = 0;
    for (int dy = -kRadius; dy <= kRadius; ++dy)
        for (int dx = -kRadius; dx <= kRadius; ++dx)
            if (dx * dx + dy * dy <= kRadius * kRadius) {
                members += 1;
                inverse += 1.0 / count_at(7 + dx, 5 + dy);
            }
    const double expected = members * members / inverse;
    EXPECT_NEAR(channel_value(out, "diagnostics.effectiveSamples", 7, 5), expected,
                1e-4 * expected);
    // Between the smallest and largest count times M, and below Σ n_j.
    EXPECT_GT(expected, 29 * 4.0);
    EXPECT_LT(expected, 29 * 6.0);
}

TEST(DenoiseDiagnostics, AnEdgeSplitsTheMembers)
{
    const int split = 6;
    const OIIO::ImageBuf out = denoise(noise_free(0.2f, 0.9f, split), diagnostic_options(2.f));
    ASSERT_FALSE(out.has_error()) << out.geterror();
    expect_diagnostics(out, split, 2.0);
    // Beside the edge only the own side counts: fewer members than the full disk.
    EXPECT_LT(channel_value(out, "diagnostics.members", split, 5), 29.f);
}

TEST(DenoiseDiagnostics, AovLayerAndNoChangeToTheResult)
{
    const OIIO::ImageBuf in = noise_free(0.2f, 0.9f, 6, "diffuse");
    DenoiseImageOptions with = diagnostic_options(2.f);
    with.aov = "diffuse";
    const OIIO::ImageBuf out = denoise(in, with);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    expect_diagnostics(out, 6, 2.0, "diffuse");
    EXPECT_GE(out.spec().channelindex("diffuse.diagnostics.members"), 0);

    DenoiseImageOptions without = with;
    without.diagnostics = false;
    const OIIO::ImageBuf plain = denoise(in, without);
    ASSERT_FALSE(plain.has_error()) << plain.geterror();
    EXPECT_EQ(plain.spec().nchannels, in.spec().nchannels);
    EXPECT_EQ(out.spec().nchannels, in.spec().nchannels + 2);
    for (const char* name : {"diffuse.R", "diffuse.G", "diffuse.B"})
        EXPECT_EQ(channel_value(out, name, 3, 4), channel_value(plain, name, 3, 4));

    // Denoising the output again rewrites the layer rather than adding a second one.
    const OIIO::ImageBuf again = denoise(out, with);
    ASSERT_FALSE(again.has_error()) << again.geterror();
    EXPECT_EQ(again.spec().nchannels, out.spec().nchannels);
    expect_diagnostics(again, 6, 2.0, "diffuse");
}

TEST(DenoiseDiagnostics, OutsideTheRoiTheLayerIsZero)
{
    const OIIO::ImageBuf out =
        denoise(noise_free(0.5f, 0.5f, kW), diagnostic_options(2.f), OIIO::ROI(4, 9, 2, 7));
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_EQ(channel_value(out, "diagnostics.members", 0, 0), 0.f);
    EXPECT_EQ(channel_value(out, "diagnostics.effectiveSamples", 12, 9), 0.f);
    // Inside, neighbours outside the ROI still count.
    EXPECT_EQ(channel_value(out, "diagnostics.members", 4, 2),
              float(expected_at(4, 2, kW, 2.0).members));
}

}  // namespace
}  // namespace statmc
