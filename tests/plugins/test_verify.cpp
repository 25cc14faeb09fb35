// The verify operator (docs/method.md §15) on synthetic statistics of known truth: a
// correct candidate is rejected at no more than the stated rate, a biased region and an
// invented edge are rejected with the power the test predicts, kept pixels are the
// candidate's bits and rejected ones the fallback's, a candidate that statmc's own
// estimate cannot reject is kept, and bad input is refused by name.
#include <cmath>
#include <random>
#include <string>

#include <OpenImageIO/imagebufalgo.h>
#include <boost/math/distributions/binomial.hpp>
#include <gtest/gtest.h>

#include "statmc/core/statistics_image.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/verify/verify.h"

namespace statmc {
namespace {

constexpr int kW = 64, kH = 64;

// The truth of pixel (x, y), channel c: a smooth ramp, brighter to the right.
double truth(int x, int, int c) { return 0.2 + 0.01 * x + 0.05 * c; }

// Samples are radiance, so never negative (core counts a negative sample as 0): uniform on
// [0, 2·truth] (σ = truth/√3), or exponential of mean truth (σ = truth, skewed).
enum class Samples { Uniform, Exponential };

double sigma(Samples kind, double t) { return kind == Samples::Uniform ? t / std::sqrt(3.0) : t; }

// n samples per pixel of expectation truth().
OIIO::ImageBuf statistics(int n, Samples kind, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    StatisticsImage<3> img(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int i = 0; i < n; ++i) {
                const double u = std::uniform_real_distribution<double>(0, 2)(rng);
                const double e = std::exponential_distribution<double>(1.0)(rng);
                float s[3];
                for (int c = 0; c < 3; ++c)
                    s[c] = float(truth(x, y, c) * (kind == Samples::Uniform ? u : e));
                img.add(x, y, s);
            }
    return layers::make_statistics_image(img.planes());
}

// A three-channel image of truth() plus `bias(x, y)` standard errors σ/√n of the mean.
template <class Bias>
OIIO::ImageBuf candidate(int n, Samples kind, Bias bias)
{
    OIIO::ImageBuf img(OIIO::ImageSpec(kW, kH, 3, OIIO::TypeFloat));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) {
                const double t = truth(x, y, c);
                const float v = float(t + bias(x, y) * sigma(kind, t) / std::sqrt(double(n)));
                static_cast<float*>(img.pixeladdr(x, y))[c] = v;
            }
    return img;
}

OIIO::ImageBuf exact_candidate(int n)
{
    return candidate(n, Samples::Uniform, [](int, int) { return 0.0; });
}

float rejected_at(const OIIO::ImageBuf& out, int x, int y)
{
    return out.getchannel(x, y, 0, out.spec().channelindex("diagnostics.rejected"));
}

// The largest count of rejections a rate of `alpha` over `trials` gives with probability
// 1 − 1e-6: the test's false-positive rate for this assertion.
double binomial_bound(double alpha, double trials)
{
    return boost::math::quantile(
        boost::math::complement(boost::math::binomial_distribution<double>(trials, alpha), 1e-6));
}

TEST(Verify, ACorrectCandidateIsRejectedAtNoMoreThanTheStatedRate)
{
    // The rate is an upper bound (Bonferroni over channels and the two tests), so only
    // exceeding it fails; 64² pixels per cell, counts from 4 to 256, normal and skewed.
    VerifyOptions opt;
    opt.test.alpha = 0.01;
    for (Samples kind : {Samples::Uniform, Samples::Exponential})
        for (int n : {4, 16, 64, 256}) {
            const OIIO::ImageBuf out =
                verify(statistics(n, kind, 100 + n), exact_candidate(n), opt);
            ASSERT_FALSE(out.has_error()) << out.geterror();
            int rejected = 0;
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    rejected += rejected_at(out, x, y) != 0;
            EXPECT_LE(rejected, binomial_bound(opt.test.alpha, kW * kH))
                << "n = " << n << (kind == Samples::Uniform ? ", uniform" : ", exponential");
            EXPECT_NEAR(out.spec().get_float_attribute(layers::attr::kVerifyRejected),
                        double(rejected) / (kW * kH), 1e-6);
        }
}

TEST(Verify, ABiasedRegionIsRejectedWithThePowerTheBoxPredicts)
{
    // A bias of 2 standard errors per pixel in a 24x24 square. One pixel alone can hardly
    // tell: its test's critical value at α/6 = 1.7e-4 (one of three channels, half of α) is
    // about 3.76, which a shift of 2 crosses with probability 0.04. The 3x3 box's mean
    // difference is 6 of its standard errors, rejected with probability 0.987 (the three
    // channels share their samples here, so they add nothing).
    const int n = 64;
    auto inside = [](int x, int y) { return x >= 20 && x < 44 && y >= 20 && y < 44; };
    const OIIO::ImageBuf out = verify(
        statistics(n, Samples::Uniform, 7),
        candidate(n, Samples::Uniform, [&](int x, int y) { return inside(x, y) ? 2.0 : 0.0; }), {});
    ASSERT_FALSE(out.has_error()) << out.geterror();
    int interior = 0, caught = 0, outside = 0, false_alarms = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool far_inside = x >= 22 && x < 42 && y >= 22 && y < 42;
            const bool far_outside = !(x >= 18 && x < 46 && y >= 18 && y < 46);
            interior += far_inside;
            caught += far_inside && rejected_at(out, x, y) != 0;
            outside += far_outside;
            false_alarms += far_outside && rejected_at(out, x, y) != 0;
        }
    EXPECT_GT(caught, 0.9 * interior);
    EXPECT_LE(false_alarms, binomial_bound(0.001, outside));
}

TEST(Verify, AnInventedEdgeIsRejected)
{
    // The truth is a smooth ramp; the candidate sharpens it into a step, 3 standard errors
    // down over the 6 columns left of x = 32 and up over the 6 right of it, as a denoiser
    // that invents an edge would. Skewed samples, n = 16. Inside each band (two columns
    // from its ends) the box's mean difference is 9 of its standard errors.
    const int n = 16;
    const OIIO::ImageBuf out =
        verify(statistics(n, Samples::Exponential, 9),
               candidate(n, Samples::Exponential,
                         [](int x, int) {
                             return x >= 26 && x < 32 ? -3.0 : x >= 32 && x < 38 ? 3.0 : 0.0;
                         }),
               {});
    ASSERT_FALSE(out.has_error()) << out.geterror();
    int band = 0, caught = 0;
    for (int y = 1; y < kH - 1; ++y)
        for (int x : {27, 28, 29, 30, 33, 34, 35, 36}) {
            ++band;
            caught += rejected_at(out, x, y) != 0;
        }
    EXPECT_GT(caught, 0.95 * band);
}

TEST(Verify, KeptPixelsAreTheCandidatesBitsAndRejectedOnesTheFallbacks)
{
    const int n = 16;
    const OIIO::ImageBuf stats = statistics(n, Samples::Uniform, 11);
    // A candidate far off in one corner, exact elsewhere.
    const OIIO::ImageBuf cand =
        candidate(n, Samples::Uniform, [](int x, int y) { return x < 8 && y < 8 ? 10.0 : 0.0; });
    for (VerifyFallback fallback : {VerifyFallback::Denoise, VerifyFallback::Mean}) {
        VerifyOptions opt;
        opt.fallback = fallback;
        const OIIO::ImageBuf out = verify(stats, cand, opt);
        ASSERT_FALSE(out.has_error()) << out.geterror();
        const OIIO::ImageBuf denoised = denoise(stats, opt.denoise);
        ASSERT_FALSE(denoised.has_error());
        int rejected = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float got = out.getchannel(x, y, 0, c);
                    if (rejected_at(out, x, y) == 0) {
                        ASSERT_EQ(got, cand.getchannel(x, y, 0, c)) << x << "," << y;
                        continue;
                    }
                    rejected += c == 0;
                    const OIIO::ImageBuf& expected =
                        fallback == VerifyFallback::Mean ? stats : denoised;
                    ASSERT_EQ(got, expected.getchannel(x, y, 0, c)) << x << "," << y;
                }
        EXPECT_GE(rejected, 60);  // the 8x8 corner, 10 standard errors off
        EXPECT_EQ(out.spec().get_int_attribute(layers::attr::kDenoised), 1);
        // Every statistics channel is kept, with one more.
        EXPECT_EQ(out.nchannels(), stats.nchannels() + 1);
    }
}

TEST(Verify, ACandidateThatStatmcsEstimateCannotRejectIsKept)
{
    // statmc's own default estimate as the candidate, tested at a level of 0.2: the smooth
    // estimate is close to the truth, so the samples alone (fallback=mean) reject it in
    // about a fifth of the pixels, as they would the truth. verify replaces a candidate only
    // where that estimate rejects it too, which it never does itself: the candidate comes
    // back whole, bit for bit.
    const OIIO::ImageBuf stats = statistics(16, Samples::Exponential, 17);
    VerifyOptions opt;
    opt.test.alpha = 0.2;
    const OIIO::ImageBuf estimate = denoise(stats, opt.denoise);
    ASSERT_FALSE(estimate.has_error()) << estimate.geterror();

    const OIIO::ImageBuf out = verify(stats, estimate, opt);
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_EQ(out.spec().get_float_attribute(layers::attr::kVerifyRejected), 0.f);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(out.getchannel(x, y, 0, c), estimate.getchannel(x, y, 0, c))
                    << x << "," << y;

    opt.fallback = VerifyFallback::Mean;
    const OIIO::ImageBuf by_samples = verify(stats, estimate, opt);
    ASSERT_FALSE(by_samples.has_error()) << by_samples.geterror();
    EXPECT_GT(by_samples.spec().get_float_attribute(layers::attr::kVerifyRejected), 0.05f);
}

TEST(Verify, BadInputIsRefusedByName)
{
    const OIIO::ImageBuf stats = statistics(8, Samples::Uniform, 13);
    OIIO::ImageBuf small(OIIO::ImageSpec(kW / 2, kH, 3, OIIO::TypeFloat));
    OIIO::ImageBuf out = verify(stats, small, {});
    EXPECT_NE(out.geterror().find(
                  "the candidate and the statistics differ in resolution: 32x64 vs 64x64"),
              std::string::npos)
        << out.geterror();

    OIIO::ImageBuf nan = exact_candidate(8);
    static_cast<float*>(nan.pixeladdr(5, 6))[1] = NAN;
    out = verify(stats, nan, {});
    EXPECT_NE(out.geterror().find("NaN or Inf at pixel (5, 6), channel 1"), std::string::npos)
        << out.geterror();

    OIIO::ImageBuf grey(OIIO::ImageSpec(kW, kH, 1, OIIO::TypeFloat));
    out = verify(stats, grey, {});
    EXPECT_NE(out.geterror().find("has no R,G,B"), std::string::npos) << out.geterror();

    // Statistics without a variance have nothing to test against.
    OIIO::ImageBuf means_only;
    const int order[] = {stats.spec().channelindex("R"), stats.spec().channelindex("G"),
                         stats.spec().channelindex("B"),
                         stats.spec().channelindex("sampleCount.Y")};
    const std::string names[] = {"R", "G", "B", "sampleCount.Y"};
    ASSERT_TRUE(OIIO::ImageBufAlgo::channels(means_only, stats, 4, order, {}, names));
    out = verify(means_only, exact_candidate(8), {});
    EXPECT_NE(out.geterror().find("variance"), std::string::npos) << out.geterror();
}

}  // namespace
}  // namespace statmc
