// The merge operator: farm tasks accumulated separately merge into exactly what one
// render of all their samples gives; mismatched or denoised inputs are refused.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/merge/merge.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

constexpr int kW = 9, kH = 7, kTasks = 3;

// Per pixel, 5..12 skewed samples (exponential around a ramp) dealt to the tasks in
// uneven shares, one task getting none on some pixels; `all` accumulates every sample.
// Each sample has a sub-pixel position, so the position co-moments merge too.
struct FarmRender {
    StatisticsImage<3> all{kW, kH, true};
    std::vector<StatisticsImage<3>> tasks{kTasks, StatisticsImage<3>(kW, kH, true)};

    FarmRender()
    {
        std::mt19937 rng(7);
        std::exponential_distribution<float> noise(1.f);
        std::uniform_real_distribution<double> position(0, 1);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int s = 0; s < 5 + (x * 3 + y) % 8; ++s) {
                    const float m = 0.2f + 0.1f * x;
                    const float sample[3] = {m * noise(rng), 2 * m * noise(rng), 0.5f};
                    const double u = position(rng), v = position(rng);
                    all.add(x, y, sample, u, v);
                    tasks[(s * (1 + x % 2) + y) % kTasks].add(x, y, sample, u, v);
                }
    }
};

// Each image goes through a file, as on the command line, so that it is named by it.
TempDir& files()
{
    static TempDir dir;
    return dir;
}

std::string path(const std::string& name) { return files().file(name); }

OIIO::ImageBuf named(const OIIO::ImageBuf& buf, const std::string& name)
{
    layers::write_image_file(buf, path(name));
    return layers::read_image_file(path(name));
}

OIIO::ImageBuf image(const StatisticsImage<3>& stats, int spp, const std::string& name)
{
    return named(layers::make_statistics_image(stats.planes(), {"", spp, 1}), name);
}

std::vector<OIIO::ImageBuf> task_images(const FarmRender& farm)
{
    std::vector<OIIO::ImageBuf> images;
    for (int k = 0; k < kTasks; ++k)
        images.push_back(image(farm.tasks[k], 10 + k, "task" + std::to_string(k) + ".exr"));
    return images;
}

std::vector<const OIIO::ImageBuf*> pointers(const std::vector<OIIO::ImageBuf>& images)
{
    std::vector<const OIIO::ImageBuf*> p;
    for (const OIIO::ImageBuf& i : images)
        p.push_back(&i);
    return p;
}

std::string merge_error(const std::vector<OIIO::ImageBuf>& images)
{
    const OIIO::ImageBuf out = merge(pointers(images));
    EXPECT_TRUE(out.has_error());
    return out.geterror();
}

TEST(Merge, FarmTasksMergeToTheAllAtOnceStatistics)
{
    const FarmRender farm;
    const std::vector<OIIO::ImageBuf> tasks = task_images(farm);
    const OIIO::ImageBuf merged = merge(pointers(tasks));
    ASSERT_FALSE(merged.has_error()) << merged.geterror();
    const OIIO::ImageBuf want = image(farm.all, 0, "all.exr");
    ASSERT_EQ(merged.spec().nchannels, want.spec().nchannels);
    EXPECT_GE(want.spec().channelindex("boxcoxCovV.B"), 0);
    EXPECT_GE(want.spec().channelindex("subpixel.UV"), 0);
    for (const std::string& name : want.spec().channelnames)
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const float w = channel_value(want, name, x, y);
                EXPECT_NEAR(channel_value(merged, name, x, y), w, 2e-5f * (1 + std::abs(w)))
                    << name << " at " << x << "," << y;
            }
    EXPECT_EQ(merged.spec().get_int_attribute(layers::attr::kSpp), 10 + 11 + 12);
    EXPECT_EQ(merged.spec().find_attribute(layers::attr::kSeed), nullptr);
}

TEST(Merge, SameBitsForAnyThreadCount)
{
    // nthreads follows ImageBufAlgo (0 = OIIO's global setting) and never changes a bit:
    // each pixel folds the parts in part order whichever thread takes it.
    const FarmRender farm;
    const std::vector<OIIO::ImageBuf> tasks = task_images(farm);
    const OIIO::ImageBuf one = merge(pointers(tasks), 1);
    ASSERT_FALSE(one.has_error()) << one.geterror();
    for (int nthreads : {0, 2, 3}) {
        const OIIO::ImageBuf other = merge(pointers(tasks), nthreads);
        ASSERT_FALSE(other.has_error()) << other.geterror();
        const auto px = [](const OIIO::ImageBuf& b) {
            std::vector<float> v(std::size_t(b.spec().image_pixels()) * b.nchannels());
            EXPECT_TRUE(b.get_pixels(b.roi(), OIIO::TypeFloat, v.data()));
            return v;
        };
        EXPECT_EQ(px(one), px(other)) << "nthreads " << nthreads;
    }
}

TEST(Merge, VarianceAovsMergeWithoutBoxCox)
{
    const FarmRender farm;
    std::vector<OIIO::ImageBuf> tasks;
    for (const OIIO::ImageBuf& t : task_images(farm))
        tasks.push_back(without_channels(
            t, {"boxcoxMean.R", "boxcoxMean.G", "boxcoxMean.B", "boxcoxVariance.R",
                "boxcoxVariance.G", "boxcoxVariance.B", "boxcoxM3.R", "boxcoxM3.G", "boxcoxM3.B"}));
    const OIIO::ImageBuf merged = merge(pointers(tasks));
    ASSERT_FALSE(merged.has_error()) << merged.geterror();
    EXPECT_LT(merged.spec().channelindex("boxcoxMean.R"), 0);
    const OIIO::ImageBuf want = image(farm.all, 0, "all.exr");
    EXPECT_NEAR(channel_value(merged, "variance.G", 4, 3), channel_value(want, "variance.G", 4, 3),
                1e-5);
    EXPECT_EQ(channel_value(merged, "sampleCount.Y", 4, 3),
              channel_value(want, "sampleCount.Y", 4, 3));
}

TEST(Merge, RefusesMismatchedResolutionAndDataWindow)
{
    const FarmRender farm;
    std::vector<OIIO::ImageBuf> tasks = task_images(farm);
    tasks[2] = image(StatisticsImage<3>(kW + 1, kH), 1, "wide.exr");
    EXPECT_NE(merge_error(tasks).find("part 2 (" + path("wide.exr") + ") and part 0 (" +
                                      path("task0.exr") +
                                      ") differ in "
                                      "resolution: 10x7 vs 9x7"),
              std::string::npos);
    tasks = task_images(farm);
    tasks[1].set_origin(3, 0);
    EXPECT_NE(merge_error(tasks).find("part 1 (" + path("task1.exr") + ") and part 0 (" +
                                      path("task0.exr") +
                                      ") differ in "
                                      "data window"),
              std::string::npos);
}

TEST(Merge, RefusesMismatchedChannelsAndVersions)
{
    const FarmRender farm;
    std::vector<OIIO::ImageBuf> tasks = task_images(farm);
    tasks[1] =
        named(without_channels(tasks[1], {"boxcoxM3.R", "boxcoxM3.G", "boxcoxM3.B"}), "task1b.exr");
    EXPECT_NE(merge_error(tasks).find("part 1 (" + path("task1b.exr") + ") and part 0 (" +
                                      path("task0.exr") + ") differ in channels"),
              std::string::npos);
    tasks = task_images(farm);
    tasks[2].specmod().attribute(layers::attr::kFormatVersion, 0);
    EXPECT_NE(merge_error(tasks).find("part 2 (" + path("task2.exr") + ") and part 0 (" +
                                      path("task0.exr") +
                                      ") differ in "
                                      "statmc:formatVersion: 0 vs 2"),
              std::string::npos);
}

TEST(Merge, RefusesDenoisedInputsAndSingleImages)
{
    const FarmRender farm;
    std::vector<OIIO::ImageBuf> tasks = task_images(farm);
    tasks[1].specmod().attribute(layers::attr::kDenoised, 1);
    EXPECT_NE(merge_error(tasks).find("part 1 (" + path("task1.exr") +
                                      ") is denoised (statmc:denoised=1)"),
              std::string::npos);
    tasks.resize(1);
    EXPECT_NE(merge_error(tasks).find("merge needs at least 2 images, got 1"), std::string::npos);
}

}  // namespace
}  // namespace statmc::test
