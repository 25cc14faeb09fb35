// statmc-render as a program: output layers and header, --denoise, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>

#include "renderer_test_support.h"

using statmc::render::test::ScratchDir;

namespace {

using statmc::render::test::ProgramRun;

ProgramRun run(const std::string& args, const ScratchDir& dir)
{
    return statmc::render::test::run_program(std::string("\"") + STATMC_RENDER_EXE + "\" " + args,
                                             dir);
}

const std::string kScene =
    "LookAt 0 0 -4  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
    "Film \"image\" \"integer xresolution\" 32 \"integer yresolution\" 16\n"
    "Sampler \"random\" \"integer pixelsamples\" 8\nWorldBegin\n"
    "AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [4 4 4]\nTranslate 0 3 0\n"
    "Shape \"sphere\" \"float radius\" 1\nAttributeEnd\n"
    "Material \"matte\" \"rgb Kd\" [0.5 0.4 0.3]\nShape \"sphere\" \"float radius\" 1\nWorldEnd\n";

}  // namespace

TEST(Cli, WritesStatisticsLayersAndHeader)
{
    ScratchDir dir("cli");
    const std::string scene = dir.write("s.pbrt", kScene);
    const ProgramRun r =
        run("\"" + scene + "\" -o \"" + dir.file("out.exr") + "\" --seed 5 --quiet --denoise", dir);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(r.output.empty()) << r.output;  // --quiet and no TTY: silent
    OIIO::ImageBuf img(dir.file("out.exr"));
    ASSERT_TRUE(img.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << img.geterror();
    const OIIO::ImageSpec& spec = img.spec();
    EXPECT_EQ(spec.width, 32);
    EXPECT_EQ(spec.height, 16);
    for (const char* ch : {"R", "G", "B", "variance.R", "boxcoxMean.G", "boxcoxVariance.B",
                           "boxcoxM3.R", "sampleCount.Y", "albedo.R", "normal.X", "depth.Z"})
        EXPECT_GE(spec.channelindex(ch), 0) << ch;
    EXPECT_EQ(spec.get_int_attribute("statmc:spp"), 8);  // the scene's pixelsamples
    EXPECT_EQ(spec.get_int_attribute("statmc:seed"), 5);
    EXPECT_GT(spec.get_float_attribute("statmc:renderTime", -1.f), 0.f);
    EXPECT_EQ(spec.get_string_attribute("statmc:scene"), scene);
    EXPECT_TRUE(std::filesystem::exists(dir.file("out.denoised.exr")));
    OIIO::ImageBuf den(dir.file("out.denoised.exr"));
    ASSERT_TRUE(den.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << den.geterror();
    EXPECT_EQ(den.spec().get_int_attribute("statmc:denoised"), 1);
}

TEST(Cli, HigherMomentsOnlyWhenAskedForAndTheRestTheSameBits)
{
    // M3, M4 and boxcoxM4 are read by no statmc stage: a file carries them on request.
    ScratchDir dir("cli-moments");
    const std::string scene = dir.write("s.pbrt", kScene);
    const std::string common = "\"" + scene + "\" --seed 5 --quiet -o ";
    ASSERT_EQ(run(common + "\"" + dir.file("plain.exr") + "\"", dir).status, 0);
    ASSERT_EQ(run(common + "\"" + dir.file("all.exr") + "\" --higher-moments", dir).status, 0);
    OIIO::ImageBuf plain(dir.file("plain.exr")), all(dir.file("all.exr"));
    ASSERT_TRUE(plain.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << plain.geterror();
    ASSERT_TRUE(all.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << all.geterror();
    for (const char* ch : {"M3.R", "M4.G", "boxcoxM4.B"}) {
        EXPECT_LT(plain.spec().channelindex(ch), 0) << ch;
        EXPECT_GE(all.spec().channelindex(ch), 0) << ch;
    }
    EXPECT_EQ(all.spec().nchannels, plain.spec().nchannels + 9);
    for (int c = 0; c < plain.spec().nchannels; ++c) {
        const std::string& name = plain.spec().channelnames[c];
        const int a = all.spec().channelindex(name);
        ASSERT_GE(a, 0) << name;
        for (int y = 0; y < plain.spec().height; ++y)
            for (int x = 0; x < plain.spec().width; ++x) {
                const float p = plain.getchannel(x, y, 0, c), q = all.getchannel(x, y, 0, a);
                ASSERT_EQ(std::memcmp(&p, &q, sizeof p), 0) << name << " at " << x << "," << y;
            }
    }
}

TEST(Cli, WriteEveryIterationEndsWithTheSameImage)
{
    // Rewriting the outputs after each iteration must not change what the render
    // accumulates: the final file equals a run that writes once.
    ScratchDir dir("cli-iter");
    const std::string scene = dir.write("s.pbrt", kScene);
    const ProgramRun once =
        run("\"" + scene + "\" -o \"" + dir.file("once.exr") + "\" --iterations 3 --quiet", dir);
    ASSERT_EQ(once.status, 0) << once.output;
    const ProgramRun each = run("\"" + scene + "\" -o \"" + dir.file("each.exr") +
                                    "\" --iterations 3 --quiet --denoise --write-every-iteration",
                                dir);
    ASSERT_EQ(each.status, 0) << each.output;
    OIIO::ImageBuf a(dir.file("once.exr")), b(dir.file("each.exr"));
    ASSERT_TRUE(a.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << a.geterror();
    ASSERT_TRUE(b.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << b.geterror();
    EXPECT_EQ(b.spec().get_int_attribute("statmc:spp"), 16);  // 4 + 4 + 8
    ASSERT_EQ(a.spec().nchannels, b.spec().nchannels);
    std::vector<float> pa(a.spec().image_pixels() * a.spec().nchannels), pb(pa.size());
    ASSERT_TRUE(a.get_pixels(a.roi(), OIIO::TypeDesc::FLOAT, pa.data()));
    ASSERT_TRUE(b.get_pixels(b.roi(), OIIO::TypeDesc::FLOAT, pb.data()));
    EXPECT_EQ(0, std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)));
    EXPECT_TRUE(std::filesystem::exists(dir.file("each.denoised.exr")));
    for (const auto& entry : std::filesystem::directory_iterator(dir.file("")))
        EXPECT_EQ(entry.path().filename().string().find("statmc-tmp"), std::string::npos)
            << entry.path();
}

TEST(Cli, ResolutionAndSppOverrides)
{
    ScratchDir dir("cli");
    const std::string scene = dir.write("s.pbrt", kScene);
    const ProgramRun r =
        run("\"" + scene + "\" -o \"" + dir.file("o.exr") + "\" --resolution 8x6 --spp 12 -q", dir);
    ASSERT_EQ(r.status, 0) << r.output;
    OIIO::ImageBuf img(dir.file("o.exr"));
    ASSERT_TRUE(img.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    EXPECT_EQ(img.spec().width, 8);
    EXPECT_EQ(img.spec().height, 6);
    EXPECT_EQ(img.spec().get_int_attribute("statmc:spp"), 12);
    EXPECT_FLOAT_EQ(img.getchannel(3, 3, 0, img.spec().channelindex("sampleCount.Y")), 12.f);
}

TEST(Cli, MalformedSceneFailsWithFileLineAndNoOutput)
{
    ScratchDir dir("cli");
    const std::string scene =
        dir.write("bad.pbrt", "WorldBegin\nShape \"sphere\" \"float radius\" [ 1\n");
    const ProgramRun r = run("\"" + scene + "\" -o \"" + dir.file("o.exr") + "\" -q", dir);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("bad.pbrt:2:"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("o.exr")));
}

TEST(Cli, ScenesWithNothingToRenderAndImpossibleSizesFailBeforeRendering)
{
    ScratchDir dir("cli");
    auto fails_with = [&](const std::string& args, const std::string& message) {
        const ProgramRun r = run(args + " -o \"" + dir.file("o.exr") + "\" -q", dir);
        EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
        EXPECT_FALSE(std::filesystem::exists(dir.file("o.exr"))) << args;
    };
    fails_with("\"" + dir.write("empty.pbrt", "") + "\"", "nothing to render");
    fails_with("\"" + dir.file("") + "\"", "is a directory, not a file");
    const std::string huge = dir.write(
        "huge.pbrt", "Film \"image\" \"integer xresolution\" 100000 \"integer yresolution\" "
                     "100000\nWorldBegin\nShape \"sphere\"\n");
    fails_with("\"" + huge + "\"", "huge.pbrt:1: Film: width and height must be in 1..65536");
    const std::string scene = dir.write("s.pbrt", kScene);
    // Within the side limit, beyond any machine's memory: refused before allocating.
    fails_with("\"" + scene + "\" --resolution 65536x65536",
               "--resolution: 65536x65536 needs about");
}

TEST(Cli, BadOptionValuesSayWhatIsExpected)
{
    ScratchDir dir("cli");
    const std::string scene = dir.write("s.pbrt", kScene);
    const ProgramRun r = run("\"" + scene + "\" -o \"" + dir.file("o.exr") + "\" --spp -1", dir);
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.output.find("--spp: must be an integer >= 1, got '-1'"), std::string::npos)
        << r.output;
    EXPECT_LT(r.output.size(), 200u) << "no 310-digit bound: " << r.output;
}

TEST(Cli, AdaptiveWritesItsCountsAndRefusesWhatItCannotDo)
{
    ScratchDir dir("cli");
    const std::string scene = dir.write("s.pbrt", kScene);
    const std::string out = dir.file("o.exr");
    const ProgramRun ok = run("\"" + scene + "\" -o \"" + out + "\" --spp 64 --adaptive", dir);
    ASSERT_EQ(ok.status, 0) << ok.output;
    EXPECT_NE(ok.output.find("adaptive: 64.0 spp on average"), std::string::npos) << ok.output;
    OIIO::ImageBuf img(out);
    ASSERT_TRUE(img.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    // Non-uniform counts: no statmc:spp, but the smallest and the mean, and the sample range
    // spans the largest count.
    EXPECT_FALSE(img.spec().find_attribute("statmc:spp"));
    const int lo = img.spec().get_int_attribute("statmc:sppMin");
    EXPECT_GE(lo, 16);
    EXPECT_LT(lo, 64);
    EXPECT_NEAR(img.spec().get_float_attribute("statmc:sppMean"), 64.f, 1e-3f);
    float largest = 0;
    for (int y = 0; y < img.spec().height; ++y)
        for (int x = 0; x < img.spec().width; ++x)
            largest = std::max(
                largest, img.getchannel(x, y, 0, img.spec().channelindex("sampleCount.Y")));
    EXPECT_EQ(img.spec().get_int_attribute("statmc:sampleEnd"), int(largest));
    std::filesystem::remove(out);

    auto fails_with = [&](const std::string& args, const std::string& message) {
        const ProgramRun r = run("\"" + scene + "\" -o \"" + out + "\" -q " + args, dir);
        EXPECT_NE(r.status, 0) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
        EXPECT_FALSE(std::filesystem::exists(out)) << args;
    };
    fails_with("--adaptive --spp 16",
               "--adaptive: 16 samples per pixel leave nothing to adapt: every pixel takes its "
               "first 16 uniformly (--adaptive-min-spp)");
    fails_with("--adaptive --spp 64 --adaptive-min-spp 64", "64 samples per pixel leave nothing");
    fails_with("--adaptive --noise-threshold -0.1",
               "--noise-threshold: must be a number >= 0, got '-0.1'");
    fails_with("--noise-threshold 0.01", "--noise-threshold requires --adaptive");
    fails_with("--adaptive --adaptive-min-rate 0", "--adaptive-min-rate");
    fails_with("--adaptive --task 0/2", "--adaptive excludes --task");
}

TEST(Cli, HelpListsEveryOptionWithItsDefault)
{
    ScratchDir dir("cli");
    const ProgramRun r = run("--help", dir);
    EXPECT_EQ(r.status, 0);
    for (const char* opt : {"--output", "--spp", "--iterations", "--resolution", "--seed",
                            "--threads", "--maxdepth", "--denoise", "--quiet"})
        EXPECT_NE(r.output.find(opt), std::string::npos) << opt;
    EXPECT_NE(r.output.find("default"), std::string::npos);
}

// Ctrl-C, and SIGTERM as schedulers send it on preemption: the render stops, and what was
// rendered is written as a valid file whose header claims no count the pixels lack.
class Interrupt : public ::testing::TestWithParam<int> {};

TEST_P(Interrupt, WritesWhatWasRenderedWithItsTrueCounts)
{
    ScratchDir dir("cli");
    const std::string scene = dir.write("s.pbrt", kScene);
    const std::string out = dir.file("o.exr");
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        const int devnull = ::open("/dev/null", O_WRONLY);
        ::dup2(devnull, 1);
        ::dup2(devnull, 2);
        ::execl(STATMC_RENDER_EXE, STATMC_RENDER_EXE, scene.c_str(), "-o", out.c_str(), "--spp",
                "10000000", "--resolution", "64x64", "--threads", "1", static_cast<char*>(nullptr));
        ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ASSERT_EQ(::kill(pid, GetParam()), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);  // interrupted, but the file is complete
    OIIO::ImageBuf img(out);
    ASSERT_TRUE(img.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << img.geterror();
    const int count = img.spec().channelindex("sampleCount.Y");
    float lo = 1e30f, hi = 0;
    double sum = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float n = img.getchannel(x, y, 0, count);
            lo = std::min(lo, n);
            hi = std::max(hi, n);
            sum += n;
        }
    EXPECT_GE(lo, 4.f);  // at least the first iteration
    EXPECT_LT(hi, 10000000.f);
    const OIIO::ImageSpec& spec = img.spec();
    if (lo == hi) {
        EXPECT_EQ(spec.get_int_attribute("statmc:spp"), int(lo));
        EXPECT_EQ(spec.find_attribute("statmc:sppMin"), nullptr);
    } else {
        EXPECT_EQ(spec.find_attribute("statmc:spp"), nullptr) << "a uniform count it lacks";
        EXPECT_EQ(spec.get_int_attribute("statmc:sppMin"), int(lo));
        EXPECT_NEAR(spec.get_float_attribute("statmc:sppMean"), sum / (64 * 64), 1e-3 * hi);
    }
}

INSTANTIATE_TEST_SUITE_P(Cli, Interrupt, ::testing::Values(SIGINT, SIGTERM),
                         [](const ::testing::TestParamInfo<int>& info) {
                             return std::string(info.param == SIGINT ? "SIGINT" : "SIGTERM");
                         });

TEST(Cli, FramesRenderASequenceWithMotionLayersAndIndependentNoise)
{
    ScratchDir dir("cli-frames");
    const std::string scene = dir.write("s.pbrt", kScene);
    const ProgramRun r = run("\"" + scene + "\" -o \"" + dir.file("shot.#.exr") +
                                 "\" --frames 3-4 --fps 24 --quiet",
                             dir);
    ASSERT_EQ(r.status, 0) << r.output;
    std::vector<std::vector<float>> red;
    for (int frame : {3, 4}) {
        OIIO::ImageBuf img(dir.file("shot.000" + std::to_string(frame) + ".exr"));
        ASSERT_TRUE(img.read(0, 0, true, OIIO::TypeDesc::FLOAT)) << img.geterror();
        EXPECT_EQ(img.spec().get_int_attribute("statmc:frame", -1), frame);
        EXPECT_GE(img.spec().channelindex("motion.X"), 0);
        EXPECT_GE(img.spec().channelindex("motion.Y"), 0);
        std::vector<float> r_channel(32 * 16);
        img.get_pixels(OIIO::ROI(0, 32, 0, 16, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT,
                       r_channel.data());
        red.push_back(r_channel);
    }
    EXPECT_NE(red[0], red[1]) << "the frames' seeds must differ";

    const ProgramRun no_pattern = run("\"" + scene + "\" -o \"" + dir.file("still.exr") +
                                          "\" --frames 1-2 --quiet",
                                      dir);
    EXPECT_NE(no_pattern.status, 0);
    EXPECT_NE(no_pattern.output.find("--frames needs a frame pattern"), std::string::npos)
        << no_pattern.output;
    const ProgramRun with_tasks = run("\"" + scene + "\" -o \"" + dir.file("t.#.exr") +
                                          "\" --frames 1-2 --tasks 2 --quiet",
                                      dir);
    EXPECT_NE(with_tasks.status, 0);
}
