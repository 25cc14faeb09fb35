// The denoise operator over frame sequences: it must denoise exactly what core's temporal
// merge makes of the frames, follow the motion layer, and refuse frames that do not match.
#include <cmath>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "shifted_statistics.h"
#include "statmc/core/temporal_merge.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"
#include "test_images.h"

namespace statmc {
namespace {

using test::channel_value;
using test::same_bits;

constexpr int kW = 37, kH = 23;

DenoiseImageOptions temporal_options(int frames)
{
    DenoiseImageOptions o = DenoiseImageOptions::classic();
    o.filter.radius = 5;
    o.filter.sigma_spatial = 4.f;
    o.temporal.frames = frames;
    return o;
}

struct Sequence {
    std::vector<StatisticsPlanes> stats;
    std::vector<OIIO::ImageBuf> images;
    test::GuideData guides = test::make_guides(kW, kH, 7);

    explicit Sequence(int frames, int spp = 8)
    {
        for (int k = 0; k < frames; ++k) {
            stats.push_back(test::noisy_statistics(kW, kH, spp, 100 + k));
            images.push_back(layers::make_statistics_image(stats.back(), {}, guides.planes()));
        }
    }
    FrameNeighbours around(int t, int reach) const
    {
        FrameNeighbours n;
        for (int k = 1; k <= reach; ++k) {
            if (t - k >= 0)
                n.previous.push_back(&images[t - k]);
            if (t + k < int(images.size()))
                n.next.push_back(&images[t + k]);
        }
        return n;
    }
};

// noisy_statistics' expectation: exponential samples of mean tint · base.
float truth(int x, int y, int c)
{
    const float tint[3] = {1.f, 0.7f, 0.4f};
    return tint[c] * float((x < kW / 2 ? 0.2 : 0.9) + 0.1 * y / kH);
}

double mse(const OIIO::ImageBuf& image)
{
    const char* names[3] = {"R", "G", "B"};
    double sum = 0;
    for (int c = 0; c < 3; ++c)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                sum += std::pow(channel_value(image, names[c], x, y) - truth(x, y, c), 2);
    return sum / (3.0 * kW * kH);
}

TEST(DenoiseTemporal, DenoisesWhatCoreMergesBitwise)
{
    const Sequence seq(3);
    const OIIO::ImageBuf out = denoise(seq.images[1], seq.around(1, 1), temporal_options(1));
    ASSERT_FALSE(out.has_error()) << out.geterror();

    std::vector<TemporalFrame> frames;
    for (const StatisticsPlanes& p : seq.stats)
        frames.push_back({p.view(), {}, {}});
    const DenoiseImageOptions opt = temporal_options(1);
    const StatisticsPlanes merged =
        merge_temporal_members(frames, 1, TestDomain::BoxCox, opt.temporal, opt.filter, 1);
    const OIIO::ImageBuf merged_image =
        layers::make_statistics_image(merged, {}, seq.guides.planes());
    const OIIO::ImageBuf expected = denoise(merged_image, temporal_options(0));
    ASSERT_FALSE(expected.has_error()) << expected.geterror();
    for (const char* name : {"R", "G", "B"})
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                ASSERT_TRUE(
                    same_bits(channel_value(out, name, x, y), channel_value(expected, name, x, y)))
                    << name << " at " << x << "," << y;
    // Only the mean changes: the frame keeps its own statistics.
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            ASSERT_EQ(channel_value(out, "sampleCount.Y", x, y),
                      channel_value(seq.images[1], "sampleCount.Y", x, y));
            ASSERT_EQ(channel_value(out, "variance.G", x, y),
                      channel_value(seq.images[1], "variance.G", x, y));
        }
}

TEST(DenoiseTemporal, NoFramesOrTemporalZeroIsTheSingleFrameDenoise)
{
    const Sequence seq(3);
    const OIIO::ImageBuf single = denoise(seq.images[1], temporal_options(0));
    const OIIO::ImageBuf off = denoise(seq.images[1], seq.around(1, 1), temporal_options(0));
    const OIIO::ImageBuf alone = denoise(seq.images[1], FrameNeighbours{}, temporal_options(2));
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            ASSERT_TRUE(same_bits(channel_value(off, "G", x, y), channel_value(single, "G", x, y)));
            ASSERT_TRUE(
                same_bits(channel_value(alone, "G", x, y), channel_value(single, "G", x, y)));
        }
}

TEST(DenoiseTemporal, MoreFramesLowerTheErrorAndNoFrameGetsWorse)
{
    // 7 frames at 4 spp; the default method (ICI ladder) per frame and with K = 2. Five
    // frames' samples predict ~5× less noise in the statistics; the filter then averages
    // less, so the output gains less: 1.5× is asked for, and every frame must stay better
    // than its noisy input.
    const Sequence seq(7, 4);
    DenoiseImageOptions per_frame;
    per_frame.filter.radius = 8;
    DenoiseImageOptions temporal = per_frame;
    temporal.temporal.frames = 2;
    double single_sum = 0, temporal_sum = 0;
    for (int t = 0; t < 7; ++t) {
        const OIIO::ImageBuf a = denoise(seq.images[t], per_frame);
        const OIIO::ImageBuf b = denoise(seq.images[t], seq.around(t, 2), temporal);
        ASSERT_FALSE(b.has_error()) << b.geterror();
        single_sum += mse(a);
        temporal_sum += mse(b);
        EXPECT_LT(mse(b), mse(seq.images[t])) << "frame " << t;
    }
    EXPECT_LT(temporal_sum * 1.5, single_sum) << temporal_sum / 7 << " vs " << single_sum / 7;
}

// `image` with a motion layer of constant (mx, my).
OIIO::ImageBuf with_motion(const OIIO::ImageBuf& image, float mx, float my)
{
    OIIO::ImageSpec spec(image.spec().width, image.spec().height, 2, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"motion.X", "motion.Y"};
    OIIO::ImageBuf motion(spec);
    const float value[2] = {mx, my};
    OIIO::ImageBufAlgo::fill(motion, value);
    return OIIO::ImageBufAlgo::channel_append(image, motion);
}

TEST(DenoiseTemporal, FollowsTheMotionLayer)
{
    // Frame t+1 is another render moved 3 px right, its motion layer saying so; the
    // result must equal the unmoved pair's wherever the filter's reach stays inside.
    const Sequence seq(2);
    const int shift = 3;
    const OIIO::ImageBuf still_next = seq.images[1];
    // The frame moves with its guides.
    test::GuideData moved_guides = seq.guides;
    for (std::vector<float>* planes :
         {&moved_guides.albedo, &moved_guides.normal, &moved_guides.depth})
        *planes = test::shifted_planes(*planes, kW, kH, shift, 0, test::Entering::EdgeCopy);
    const StatisticsPlanes moved_stats =
        test::shifted(seq.stats[1], shift, 0, test::Entering::EdgeCopy);
    const OIIO::ImageBuf moved_next = with_motion(
        layers::make_statistics_image(moved_stats, {}, moved_guides.planes()), float(-shift), 0.f);
    const OIIO::ImageBuf centre_still = seq.images[0];
    const OIIO::ImageBuf centre_moving = with_motion(seq.images[0], 0.f, 0.f);

    const OIIO::ImageBuf a =
        denoise(centre_still, FrameNeighbours{{}, {&still_next}}, temporal_options(1));
    const OIIO::ImageBuf b =
        denoise(centre_moving, FrameNeighbours{{}, {&moved_next}}, temporal_options(1));
    ASSERT_FALSE(a.has_error()) << a.geterror();
    ASSERT_FALSE(b.has_error()) << b.geterror();
    const int reach = temporal_options(1).filter.radius;
    int compared = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x + shift + reach < kW; ++x, ++compared)
            ASSERT_TRUE(same_bits(channel_value(a, "G", x, y), channel_value(b, "G", x, y)))
                << x << "," << y;
    EXPECT_GT(compared, kW * kH / 2);
    // Without the motion layer the moved frame's edge lands 3 px off and is refused, so
    // the results differ there.
    const OIIO::ImageBuf moved_unlabelled =
        layers::make_statistics_image(moved_stats, {}, moved_guides.planes());
    const OIIO::ImageBuf c =
        denoise(centre_still, FrameNeighbours{{}, {&moved_unlabelled}}, temporal_options(1));
    int differ = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            differ += !same_bits(channel_value(a, "G", x, y), channel_value(c, "G", x, y));
    EXPECT_GT(differ, 0);
}

void expect_error(const OIIO::ImageBuf& centre, const FrameNeighbours& neighbours,
                  const std::string& message)
{
    const OIIO::ImageBuf out = denoise(centre, neighbours, temporal_options(1));
    ASSERT_TRUE(out.has_error());
    EXPECT_NE(out.geterror().find(message), std::string::npos) << out.geterror();
}

TEST(DenoiseTemporal, MismatchedFramesAreErrorsNamingTheFrame)
{
    const Sequence seq(2);
    const StatisticsPlanes small = test::noisy_statistics(kW - 1, kH, 8, 3);
    const OIIO::ImageBuf small_image = layers::make_statistics_image(small);
    expect_error(seq.images[0], {{}, {&small_image}}, "frame t+1");
    expect_error(seq.images[0], {{}, {&small_image}}, "resolution");

    OIIO::ImageBuf shifted_window = seq.images[1];
    shifted_window.set_origin(2, 0);
    expect_error(seq.images[0], {{&shifted_window}, {}}, "frame t−1");
    expect_error(seq.images[0], {{&shifted_window}, {}}, "data window");

    const OIIO::ImageBuf moving = with_motion(seq.images[1], 1.f, 0.f);
    expect_error(seq.images[0], {{}, {&moving}}, "motion layer (motion.X, motion.Y) is in");

    const OIIO::ImageBuf lacking = test::without_channels(
        seq.images[1],
        {"boxcoxMean.R", "boxcoxMean.G", "boxcoxMean.B", "boxcoxVariance.R", "boxcoxVariance.G",
         "boxcoxVariance.B", "boxcoxM3.R", "boxcoxM3.G", "boxcoxM3.B"});
    expect_error(seq.images[0], {{}, {&lacking}}, "boxcox");
}

// `noise` with the pixels of rows [0, rows) taken from `from`: a static region of a shot
// rendered with one seed in every frame.
OIIO::ImageBuf with_rows_of(const OIIO::ImageBuf& noise, const OIIO::ImageBuf& from, int rows)
{
    OIIO::ImageBuf out = noise;
    OIIO::ImageBufAlgo::paste(out, 0, 0, 0, 0, from, OIIO::ROI(0, kW, 0, rows));
    return out;
}

TEST(DenoiseTemporal, FramesThatShareTheirSamplesAreRefused)
{
    const Sequence seq(2);
    // The centre itself as its neighbour: every noisy pixel repeated.
    expect_error(seq.images[0], {{}, {&seq.images[0]}},
                 "frame t+1: it and the frame denoised repeat the same noise in");
    expect_error(seq.images[0], {{}, {&seq.images[0]}}, "rendered with one seed");
    // More than half the rows repeated is refused, a third is not (and merges as before).
    const OIIO::ImageBuf most = with_rows_of(seq.images[1], seq.images[0], kH * 2 / 3);
    expect_error(seq.images[0], {{&most}, {}}, "frame t−1: it and the frame denoised repeat");
    const OIIO::ImageBuf third = with_rows_of(seq.images[1], seq.images[0], kH / 3);
    EXPECT_FALSE(
        denoise(seq.images[0], FrameNeighbours{{&third}, {}}, temporal_options(1)).has_error());

    // The headers: one seed and overlapping sample ranges are the same samples.
    OIIO::ImageBuf a = seq.images[0], b = seq.images[1];
    for (OIIO::ImageBuf* f : {&a, &b}) {
        f->specmod().attribute("statmc:seed", 3);
        f->specmod().attribute("statmc:spp", 8);
    }
    expect_error(a, {{}, {&b}}, "frame t+1: it and the frame denoised drew the same samples (seed 3, "
                                "samples 0..7): merged over time they would count twice");
    b.specmod().attribute("statmc:seed", 4);
    EXPECT_FALSE(denoise(a, FrameNeighbours{{}, {&b}}, temporal_options(1)).has_error());
    // Disjoint ranges of one seed are different samples.
    b.specmod().attribute("statmc:seed", 3);
    b.specmod().attribute("statmc:sampleBegin", 8);
    b.specmod().attribute("statmc:sampleEnd", 16);
    EXPECT_FALSE(denoise(a, FrameNeighbours{{}, {&b}}, temporal_options(1)).has_error());
    // Frames of an older statmc-render sequence: the sequence's seed with the frame numbers
    // it was mixed with.
    b.specmod().erase_attribute("statmc:sampleBegin");
    b.specmod().erase_attribute("statmc:sampleEnd");
    a.specmod().attribute("statmc:frame", 1);
    b.specmod().attribute("statmc:frame", 2);
    EXPECT_FALSE(denoise(a, FrameNeighbours{{}, {&b}}, temporal_options(1)).has_error());
    b.specmod().attribute("statmc:frame", 1);
    expect_error(a, {{}, {&b}}, "drew the same samples");
}

TEST(DenoiseTemporal, BitwiseTheSameForAnyThreadCount)
{
    const Sequence seq(5);
    DenoiseImageOptions opt;
    opt.temporal.frames = 2;
    opt.temporal.radius = 1;
    const OIIO::ImageBuf one = denoise(seq.images[2], seq.around(2, 2), opt, {}, 1);
    const OIIO::ImageBuf all = denoise(seq.images[2], seq.around(2, 2), opt, {}, 0);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            ASSERT_TRUE(same_bits(channel_value(one, "B", x, y), channel_value(all, "B", x, y)));
}

}  // namespace
}  // namespace statmc
