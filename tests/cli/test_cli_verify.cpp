// --verify and --oidn from the command line: the tool's result is the operator's, bad
// input is refused by name without writing anything, and --oidn without OIDN says how to
// get it. (With OIDN present, test_cli_oidn.cpp runs it.)
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>

#include "statmc/verify/verify.h"

#include "cli_images.h"
#include "cli_runner.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

// The statistics image's means, brightened by 20% in its left third: a candidate that
// is right on two thirds of the frame and wrong on one.
OIIO::ImageBuf partly_wrong_candidate(const OIIO::ImageBuf& stats)
{
    OIIO::ImageBuf out(
        OIIO::ImageSpec(stats.spec().width, stats.spec().height, 3, OIIO::TypeFloat));
    for (int y = 0; y < stats.spec().height; ++y)
        for (int x = 0; x < stats.spec().width; ++x)
            for (int c = 0; c < 3; ++c)
                static_cast<float*>(out.pixeladdr(x, y))[c] =
                    stats.getchannel(x, y, 0, c) * (x < stats.spec().width / 3 ? 1.2f : 1.f);
    return out;
}

TEST(CliVerify, TheToolsResultIsTheOperators)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    const OIIO::ImageBuf stats = read_exr(dir.file("frame.exr"));
    write_exr(partly_wrong_candidate(stats), dir.file("candidate.exr"));
    const CliResult r = run_cli({dir.file("frame.exr"), dir.file("candidate.exr"),
                                 "--verify:alpha=0.01", "-o", dir.file("out.exr")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("verify: " + dir.file("candidate.exr") + " rejected at "),
              std::string::npos)
        << r.out;
    VerifyOptions opt;
    opt.test.alpha = 0.01;
    const OIIO::ImageBuf want = verify(stats, read_exr(dir.file("candidate.exr")), opt);
    ASSERT_FALSE(want.has_error()) << want.geterror();
    expect_same_channels(read_exr(dir.file("out.exr")), want);
}

TEST(CliVerify, BadInputIsRefusedAndNothingIsWritten)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    write_exr(cli_render(0, kCliWidth - 1, kCliHeight), dir.file("small.exr"));
    CliResult r = run_cli(
        {dir.file("frame.exr"), dir.file("small.exr"), "--verify", "-o", dir.file("out.exr")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("the candidate (" + dir.file("small.exr") + ") and the statistics (" +
                         dir.file("frame.exr") + ") differ in resolution: 23x16 vs 24x16"),
              std::string::npos)
        << r.err;
    r = run_cli({dir.file("frame.exr"), "--verify", "-o", dir.file("out.exr")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("--verify: needs 2 images, the stack holds 1"), std::string::npos)
        << r.err;
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"frame.exr", "small.exr"}));
}

TEST(CliVerify, OidnWithoutItsLibrarySaysHowToGetIt)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    const CliResult r =
        run_cli({dir.file("frame.exr"), "--oidn:library=" + dir.file("libOpenImageDenoise.so.2"),
                 "-o", dir.file("out.exr")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.err.find("OIDN (Intel Open Image Denoise 2) is not installed"), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("pip install pyoidn"), std::string::npos) << r.err;
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"frame.exr"}));
}

TEST(CliVerify, DupPushesACopyOfTheTopImage)
{
    TempDir dir;
    write_exr(cli_render(0), dir.file("frame.exr"));
    // f, a copy doubled, subtracted: -f. Had --dup pushed the same image twice, the
    // doubling would have doubled both and left 0.
    const CliResult r = run_cli(
        {dir.file("frame.exr"), "--dup", "--mulc", "2", "--sub", "-o", dir.file("minus.exr")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const OIIO::ImageBuf one = read_exr(dir.file("frame.exr"));
    const OIIO::ImageBuf minus = read_exr(dir.file("minus.exr"));
    ASSERT_EQ(minus.nchannels(), one.nchannels());
    for (int c = 0; c < one.nchannels(); ++c)
        for (int y = 0; y < kCliHeight; ++y)
            for (int x = 0; x < kCliWidth; ++x)
                ASSERT_EQ(minus.getchannel(x, y, 0, c), -one.getchannel(x, y, 0, c));
}

}  // namespace
}  // namespace statmc::test
