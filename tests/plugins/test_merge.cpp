// The merge operator: farm tasks accumulated separately merge into exactly what one
// render of all their samples gives; mismatched or denoised inputs are refused.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/sample_provenance.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/merge/merge.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

constexpr int kW = 9, kH = 7, kTasks = 3;

// Per pixel, 5..12 skewed samples (exponential around a ramp) dealt to the tasks in
// uneven shares, one task getting none on some pixels; `all` accumulates every sample.
struct FarmRender {
    StatisticsImage<3> all{kW, kH};
    std::vector<StatisticsImage<3>> tasks{kTasks, StatisticsImage<3>(kW, kH)};

    FarmRender()
    {
        std::mt19937 rng(7);
        std::exponential_distribution<float> noise(1.f);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int s = 0; s < 5 + (x * 3 + y) % 8; ++s) {
                    const float m = 0.2f + 0.1f * x;
                    const float sample[3] = {m * noise(rng), 2 * m * noise(rng), 0.5f};
                    all.add(x, y, sample);
                    tasks[(s * (1 + x % 2) + y) % kTasks].add(x, y, sample);
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

// Seed `seed` draws samples 0..spp-1 (a render without the range attributes).
OIIO::ImageBuf image(const StatisticsImage<3>& stats, int spp, const std::string& name,
                     int seed = 1)
{
    return named(layers::make_statistics_image(stats.planes(), {"", spp, seed}), name);
}

std::vector<OIIO::ImageBuf> task_images(const FarmRender& farm)
{
    std::vector<OIIO::ImageBuf> images;
    for (int k = 0; k < kTasks; ++k)
        images.push_back(
            image(farm.tasks[k], 10 + k, "task" + std::to_string(k) + ".exr", 100 + k));
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
    EXPECT_GE(want.spec().channelindex("M4.B"), 0);
    EXPECT_GE(want.spec().channelindex("boxcoxM4.B"), 0);
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

TEST(Merge, GuideVariancesPoolExactly)
{
    // Parts with different guide means and spreads: the merged albedoVariance is the
    // summed per-sample variance of all their albedo samples together, as one render of
    // them all would write it.
    const FarmRender farm;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    std::vector<std::vector<float>> albedo(kTasks, std::vector<float>(std::size_t(kW) * kH * 3));
    std::vector<std::vector<float>> variance(kTasks, std::vector<float>(std::size_t(kW) * kH));
    std::vector<OIIO::ImageBuf> parts;
    const std::size_t n = std::size_t(kW) * kH;
    std::vector<double> sum_all(n * 3), squares_all(n), count_all(n);
    for (int k = 0; k < kTasks; ++k) {
        const StatisticsPlanes planes = farm.tasks[k].planes();
        for (std::size_t i = 0; i < n; ++i) {
            const int count = int(planes.count[i]);
            double sum[3] = {}, squares = 0;
            for (int s = 0; s < count; ++s)
                for (int c = 0; c < 3; ++c) {
                    const double a = 0.3 * k + 0.2 * u(rng);
                    sum[c] += a;
                    squares += a * a;
                }
            double mean_squares = 0;
            for (int c = 0; c < 3; ++c) {
                albedo[k][c * n + i] = count > 0 ? float(sum[c] / count) : 0.f;
                mean_squares += count > 0 ? sum[c] * sum[c] / count : 0;
                sum_all[c * n + i] += sum[c];
            }
            variance[k][i] = count > 1 ? float((squares - mean_squares) / (count - 1)) : 0.f;
            squares_all[i] += squares;
            count_all[i] += count;
        }
        layers::GuidePlanes guides;
        for (int c = 0; c < 3; ++c)
            guides.albedo[c] = dense_plane(albedo[k].data() + c * n, kW);
        guides.albedo_variance = dense_plane(variance[k].data(), kW);
        parts.push_back(named(
            layers::make_statistics_image(farm.tasks[k].planes(), {"", 10 + k, 100 + k}, guides),
            "guided" + std::to_string(k) + ".exr"));
    }
    const OIIO::ImageBuf merged = merge(pointers(parts));
    ASSERT_FALSE(merged.has_error()) << merged.geterror();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const std::size_t i = std::size_t(y) * kW + x;
            double mean_squares = 0;
            for (int c = 0; c < 3; ++c)
                mean_squares += sum_all[c * n + i] * sum_all[c * n + i] / count_all[i];
            const double want = (squares_all[i] - mean_squares) / (count_all[i] - 1);
            EXPECT_NEAR(channel_value(merged, "albedoVariance.Y", x, y), want, 1e-5 * (1 + want))
                << x << "," << y;
        }
}

TEST(Merge, SameBitsForAnyThreadCount)
{
    // nthreads follows ImageBufAlgo (0 = OIIO's global setting) and never changes a bit:
    // each pixel folds the parts in part order whichever thread takes it.
    const FarmRender farm;
    const std::vector<OIIO::ImageBuf> tasks = task_images(farm);
    const OIIO::ImageBuf one = merge(pointers(tasks), {}, 1);
    ASSERT_FALSE(one.has_error()) << one.geterror();
    for (int nthreads : {0, 2, 3}) {
        const OIIO::ImageBuf other = merge(pointers(tasks), {}, nthreads);
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

// Farm task k of `count` with `seed`: samples 10k..10k+9 (the header is what is checked).
OIIO::ImageBuf task_image(const FarmRender& farm, int k, int count, int seed = 5)
{
    OIIO::ImageBuf img =
        layers::make_statistics_image(farm.tasks[k % kTasks].planes(), {"", 10, seed});
    layers::write_sample_provenance(img.specmod(),
                                    {seed, layers::SampleRange{10 * k, 10 * k + 10}, k, count});
    return named(img, "farm-task" + std::to_string(k) + "-of-" + std::to_string(count) + "-seed" +
                          std::to_string(seed) + ".exr");
}

TEST(Merge, RefusesTheSameSamplesTwice)
{
    const FarmRender farm;
    // Seed 1 drew samples 0..9 in one part and 0..10 in the other.
    const std::vector<OIIO::ImageBuf> parts = {image(farm.tasks[0], 10, "seed1-a.exr", 1),
                                               image(farm.tasks[1], 11, "seed1-b.exr", 1)};
    EXPECT_NE(merge_error(parts).find("part 0 (" + path("seed1-a.exr") +
                                      ": seed 1, samples 0..9) and part 1 (" + path("seed1-b.exr") +
                                      ": seed 1, samples 0..10) drew the same samples"),
              std::string::npos)
        << merge_error(parts);
}

TEST(Merge, CompleteTaskSetKeepsSeedAndSampleRange)
{
    const FarmRender farm;
    const std::vector<OIIO::ImageBuf> parts = {task_image(farm, 1, 3), task_image(farm, 0, 3),
                                               task_image(farm, 2, 3)};
    const OIIO::ImageBuf merged = merge(pointers(parts));
    ASSERT_FALSE(merged.has_error()) << merged.geterror();
    const OIIO::ImageSpec& spec = merged.spec();
    EXPECT_EQ(spec.get_int_attribute(layers::attr::kSeed, -1), 5);
    EXPECT_EQ(spec.get_int_attribute(layers::attr::kSampleBegin, -1), 0);
    EXPECT_EQ(spec.get_int_attribute(layers::attr::kSampleEnd, -1), 30);
    EXPECT_EQ(spec.get_int_attribute(layers::attr::kSpp, -1), 30);
    EXPECT_EQ(spec.find_attribute(layers::attr::kTaskIndex), nullptr);
    EXPECT_EQ(spec.find_attribute(layers::attr::kTasksMissing), nullptr);
}

TEST(Merge, RefusesInconsistentAndIncompleteTaskSets)
{
    const FarmRender farm;
    auto error_of = [](const std::vector<OIIO::ImageBuf>& parts) { return merge_error(parts); };
    EXPECT_NE(error_of({task_image(farm, 0, 4), task_image(farm, 1, 4), task_image(farm, 3, 4)})
                  .find("the task set is incomplete: 1 of 4 tasks missing (task 2)"),
              std::string::npos);
    EXPECT_NE(error_of({task_image(farm, 0, 2), task_image(farm, 1, 3)})
                  .find("split the frame into different task counts"),
              std::string::npos);
    EXPECT_NE(error_of({task_image(farm, 0, 2, 5), task_image(farm, 1, 2, 6)})
                  .find("are tasks of one frame with different seeds"),
              std::string::npos);
    // The same task twice under another name: refused as a duplicate sample range first.
    OIIO::ImageBuf copy = task_image(farm, 1, 2);
    const OIIO::ImageBuf twice = named(copy, "copy.exr");
    EXPECT_NE(error_of({task_image(farm, 0, 2), task_image(farm, 1, 2), twice})
                  .find("drew the same samples"),
              std::string::npos);
    // A task stopped early: its header has statmc:sppMin, not statmc:spp = 10.
    OIIO::ImageBuf stopped = task_image(farm, 1, 2);
    stopped.specmod().erase_attribute(layers::attr::kSpp);
    stopped.specmod().attribute(layers::attr::kSppMin, 4);
    EXPECT_NE(error_of({task_image(farm, 0, 2), named(stopped, "stopped.exr")})
                  .find("part 1 (" + path("stopped.exr") +
                        ": seed 5, samples 10..19, task 1/2) stopped before its last sample"),
              std::string::npos)
        << error_of({task_image(farm, 0, 2), named(stopped, "stopped.exr")});
    OIIO::ImageBuf bad_index = task_image(farm, 1, 2);
    bad_index.specmod().attribute(layers::attr::kTaskIndex, 2);
    EXPECT_NE(error_of({task_image(farm, 0, 2), named(bad_index, "bad-index.exr")})
                  .find("task 2 of 2 (statmc:taskIndex, statmc:taskCount) is not a task"),
              std::string::npos);
}

TEST(Merge, RefusesATaskFileThatIsNotItsTasksShare)
{
    // Task 1 of 2 written after 5 of its 10 samples (--write-every-iteration): its header
    // says samples 10..14 and statmc:spp 5, complete in itself, but not task 1's share.
    const FarmRender farm;
    OIIO::ImageBuf early = layers::make_statistics_image(farm.tasks[1].planes(), {"", 5, 5});
    layers::write_sample_provenance(early.specmod(), {5, layers::SampleRange{10, 15}, 1, 2});
    const std::vector<OIIO::ImageBuf> parts = {task_image(farm, 0, 2), named(early, "early.exr")};
    EXPECT_NE(merge_error(parts).find("the tasks do not split one frame of 15 samples: part 0 (" +
                                      path("farm-task0-of-2-seed5.exr") +
                                      ": seed 5, samples 0..9, task 0/2) holds other samples "
                                      "than task 0's share (0..6)"),
              std::string::npos)
        << merge_error(parts);
}

TEST(Merge, AllowPartialMergesWhatIsThereAndCountsTheMissing)
{
    const FarmRender farm;
    const std::vector<OIIO::ImageBuf> parts = {task_image(farm, 0, 4), task_image(farm, 2, 4)};
    MergeOptions options;
    options.allow_partial = true;
    const OIIO::ImageBuf merged = merge(pointers(parts), options);
    ASSERT_FALSE(merged.has_error()) << merged.geterror();
    EXPECT_EQ(merged.spec().get_int_attribute(layers::attr::kTasksMissing), 2);
    EXPECT_EQ(merged.spec().get_int_attribute(layers::attr::kSpp), 20);
    EXPECT_EQ(merged.spec().find_attribute(layers::attr::kSampleBegin), nullptr)
        << "samples 0..9 and 20..29 are not one range";
    EXPECT_EQ(merged.spec().find_attribute(layers::attr::kSeed), nullptr)
        << "a seed without its range would read back as samples 0..19";
    const std::vector<OIIO::ImageBuf> one = {task_image(farm, 3, 4)};
    const OIIO::ImageBuf alone = merge(pointers(one), options);
    ASSERT_FALSE(alone.has_error()) << alone.geterror();
    EXPECT_EQ(alone.spec().get_int_attribute(layers::attr::kTasksMissing), 3);
}

TEST(Merge, DepthGuideIsTheSampleWeightedMean)
{
    const FarmRender farm;
    std::vector<float> depth_a(std::size_t(kW) * kH, 1.f), depth_b(std::size_t(kW) * kH, 4.f);
    layers::GuidePlanes ga, gb;
    ga.depth = dense_plane(depth_a.data(), kW);
    gb.depth = dense_plane(depth_b.data(), kW);
    const std::vector<OIIO::ImageBuf> parts = {
        named(layers::make_statistics_image(farm.tasks[0].planes(), {"", 1, 1}, ga), "da.exr"),
        named(layers::make_statistics_image(farm.tasks[1].planes(), {"", 1, 2}, gb), "db.exr")};
    const OIIO::ImageBuf merged = merge(pointers(parts));
    ASSERT_FALSE(merged.has_error()) << merged.geterror();
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double na = farm.tasks[0].at(x, y).n, nb = farm.tasks[1].at(x, y).n;
            const double want = na + nb > 0 ? (na * 1 + nb * 4) / (na + nb) : 0;
            EXPECT_NEAR(channel_value(merged, "depth.Z", x, y), want, 1e-6) << x << "," << y;
        }
}

}  // namespace
}  // namespace statmc::test
