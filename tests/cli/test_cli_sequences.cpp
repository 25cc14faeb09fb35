// Frame sequences on the command line: oiiotool's patterns and --frames, one run of the
// program per frame, and --denoise:temporal reading the frames around each.
#include <algorithm>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "cli_images.h"
#include "cli_runner.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

class CliSequence : public ::testing::Test {
protected:
    // Statistics frames that differ in their noise, written as name(frame).
    std::vector<std::string> write_frames(const std::string& printf_name,
                                          const std::vector<int>& frames)
    {
        std::vector<std::string> paths;
        for (int f : frames) {
            char name[256];
            std::snprintf(name, sizeof name, printf_name.c_str(), f);
            const StatisticsPlanes stats = noisy_statistics(kCliWidth, kCliHeight, 8, 300 + f);
            write_exr(layers::make_statistics_image(stats, {},
                                                    make_guides(kCliWidth, kCliHeight, 9).planes()),
                      dir.file(name));
            paths.push_back(dir.file(name));
        }
        return paths;
    }

    void expect_ok(const CliResult& r)
    {
        EXPECT_EQ(r.exit_code, 0) << r.err;
        EXPECT_FALSE(r.timed_out);
    }

    void expect_error(const CliResult& r, const std::string& message)
    {
        EXPECT_EQ(r.exit_code, 1) << r.err;
        EXPECT_EQ(r.err.rfind("statmc: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << "expected \"" << message << "\" in:\n"
                                                          << r.err;
    }

    bool has(const std::string& name) const
    {
        const auto e = dir.entries();
        return std::find(e.begin(), e.end(), name) != e.end();
    }

    TempDir dir;
};

TEST_F(CliSequence, HashAtAndPrintfPatternsRunEachFrame)
{
    write_frames("shot.%04d.exr", {1, 2, 3});
    expect_ok(run_cli({dir.file("shot.#.exr"), "--frames", "1-3", "-o", dir.file("a.#.exr")}));
    expect_ok(run_cli({dir.file("shot.%04d.exr"), "--frames", "2,3", "-o", dir.file("b.@@.exr")}));
    expect_ok(run_cli({dir.file("shot.@@@@.exr"), "-o", dir.file("c.%03d.exr")}));  // on disk
    for (const char* name : {"a.0001.exr", "a.0002.exr", "a.0003.exr", "b.02.exr", "b.03.exr",
                             "c.001.exr", "c.002.exr", "c.003.exr"})
        EXPECT_TRUE(has(name)) << name;
    EXPECT_FALSE(has("b.01.exr"));
    // Each output is its own frame.
    EXPECT_EQ(file_bytes(dir.file("a.0002.exr")), file_bytes(dir.file("shot.0002.exr")));
}

TEST_F(CliSequence, TemporalDenoiseReadsTheFramesAround)
{
    const auto paths = write_frames("shot.%04d.exr", {1, 2, 3, 4});
    expect_ok(run_cli({dir.file("shot.#.exr"), "--frames", "1-4", "--denoise:temporal=1", "-o",
                       dir.file("out.#.exr")}));
    // Frame 2 is what the API makes of frames 1..3, frame 4 of 3..4 (the sequence's end).
    std::vector<OIIO::ImageBuf> in;
    for (const std::string& p : paths)
        in.push_back(read_exr(p));
    DenoiseImageOptions opt;
    opt.temporal.frames = 1;
    const OIIO::ImageBuf two = denoise(in[1], FrameNeighbours{{&in[0]}, {&in[2]}}, opt);
    const OIIO::ImageBuf four = denoise(in[3], FrameNeighbours{{&in[2]}, {}}, opt);
    const OIIO::ImageBuf alone = denoise(in[1], DenoiseImageOptions{});
    const OIIO::ImageBuf out2 = read_exr(dir.file("out.0002.exr"));
    const OIIO::ImageBuf out4 = read_exr(dir.file("out.0004.exr"));
    int differs_from_single = 0;
    for (int y = 0; y < kCliHeight; ++y)
        for (int x = 0; x < kCliWidth; ++x) {
            ASSERT_TRUE(same_bits(channel_value(out2, "G", x, y), channel_value(two, "G", x, y)));
            ASSERT_TRUE(same_bits(channel_value(out4, "G", x, y), channel_value(four, "G", x, y)));
            differs_from_single +=
                !same_bits(channel_value(out2, "G", x, y), channel_value(alone, "G", x, y));
        }
    EXPECT_GT(differs_from_single, kCliWidth * kCliHeight / 2);
}

TEST_F(CliSequence, AMissingFrameIsAnErrorUnlessSkipped)
{
    write_frames("shot.%04d.exr", {1, 2, 4});
    const CliResult r = run_cli(
        {dir.file("shot.#.exr"), "--frames", "1-4", "--denoise", "-o", dir.file("out.#.exr")});
    expect_error(r, "shot.0003.exr: frame 3 of the sequence is missing: no such file");
    EXPECT_FALSE(has("out.0001.exr"));  // checked before any frame runs

    const CliResult skipped = run_cli({dir.file("shot.#.exr"), "--frames", "1-4", "--skip-missing",
                                       "--denoise:temporal=1", "-o", dir.file("out.#.exr")});
    expect_ok(skipped);
    EXPECT_NE(skipped.err.find("skipping frame 3"), std::string::npos) << skipped.err;
    EXPECT_TRUE(has("out.0004.exr"));
    EXPECT_FALSE(has("out.0003.exr"));
}

TEST_F(CliSequence, BadSequencesAreClearErrorsWithNoOutput)
{
    expect_error(run_cli({dir.file("none.#.exr"), "-o", dir.file("out.#.exr")}),
                 "the frame pattern matches no file");
    write_frames("shot.%04d.exr", {1, 2});
    expect_error(run_cli({dir.file("shot.0001.exr"), "--frames", "1-2", "-o", dir.file("o.exr")}),
                 "--frames: no input or output names a frame pattern");
    expect_error(run_cli({dir.file("shot.#.exr"), "--frames", "two", "-o", dir.file("o.#.exr")}),
                 "--frames: cannot read 'two' as frames");
    expect_error(
        run_cli({dir.file("shot.0001.exr"), "--denoise:temporal=1", "-o", dir.file("o.exr")}),
        "temporal=1 needs a frame sequence");
    // A changed image is no longer the frame as read: its neighbours would not match it.
    expect_error(run_cli({dir.file("shot.#.exr"), "--subimage", "0", "--denoise:temporal=1", "-o",
                          dir.file("o.#.exr")}),
                 "temporal=1 needs a frame sequence");
    EXPECT_FALSE(has("o.exr"));
    EXPECT_FALSE(has("o.0001.exr"));
}

TEST_F(CliSequence, FramesThatDoNotMatchStopTheRunBeforeAnyOutput)
{
    write_frames("shot.%04d.exr", {1, 2, 3});
    // Frame 3 has other channels: a motion layer the others lack.
    OIIO::ImageBuf odd = read_exr(dir.file("shot.0003.exr"));
    OIIO::ImageSpec spec(kCliWidth, kCliHeight, 2, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"motion.X", "motion.Y"};
    OIIO::ImageBuf motion(spec);
    OIIO::ImageBufAlgo::zero(motion);
    write_exr(OIIO::ImageBufAlgo::channel_append(odd, motion), dir.file("shot.0003.exr"));

    const CliResult r = run_cli({dir.file("shot.#.exr"), "--frames", "1-3", "--denoise:temporal=1",
                                 "-o", dir.file("out.#.exr")});
    expect_error(r, "only in " + dir.file("shot.0003.exr") + ": motion.X, motion.Y");
    EXPECT_FALSE(has("out.0001.exr"));

    // Another resolution.
    write_exr(layers::make_statistics_image(noisy_statistics(kCliWidth + 1, kCliHeight, 8, 1)),
              dir.file("shot.0003.exr"));
    expect_error(run_cli({dir.file("shot.#.exr"), "--frames", "1-3", "--denoise:temporal=2", "-o",
                          dir.file("out.#.exr")}),
                 "differ in resolution");
    EXPECT_FALSE(has("out.0001.exr"));
}

}  // namespace
}  // namespace statmc::test
