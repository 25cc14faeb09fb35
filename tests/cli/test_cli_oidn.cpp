// --oidn with OIDN's library present (built only with STATMC_TEST_OIDN; the library is the
// one scripts/install-test-deps.sh installs with pyoidn, or STATMC_OIDN_LIBRARY): it runs,
// gives the same bits on every run, and `--dup --oidn --verify` is verify() of its output.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>

#include "statmc/oidn/oidn.h"
#include "statmc/verify/verify.h"

#include "cli_images.h"
#include "cli_runner.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

const std::string kLibrary = STATMC_TEST_OIDN_LIBRARY;

// Points the statmc processes (and this one) at the test's OIDN, failing loudly when the
// build found none: these tests must not pass by skipping.
class OidnLibrary : public ::testing::Test {
protected:
    void SetUp() override
    {
        ASSERT_FALSE(kLibrary.empty() || !std::filesystem::exists(kLibrary))
            << "the OIDN tests need OIDN's library (" << kLibrary
            << "): run scripts/install-test-deps.sh, or configure with -DSTATMC_TEST_OIDN=OFF";
        setenv("STATMC_OIDN_LIBRARY", kLibrary.c_str(), 1);
    }
    void TearDown() override { unsetenv("STATMC_OIDN_LIBRARY"); }
};

TEST_F(OidnLibrary, RunsGivesTheSameBitsTwiceAndAChainedVerifyIsVerifyOfItsOutput)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    for (const char* out : {"oidn1.exr", "oidn2.exr"}) {
        const CliResult r = run_cli({dir.file("frame.exr"), "--oidn", "-o", dir.file(out)});
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const OIIO::ImageBuf frame = read_exr(dir.file("frame.exr"));
    const OIIO::ImageBuf first = read_exr(dir.file("oidn1.exr"));
    expect_same_channels(read_exr(dir.file("oidn2.exr")), first);
    // The library gives the tool's bits, and it changed the beauty.
    const OIIO::ImageBuf direct = oidn_denoise(frame);
    ASSERT_FALSE(direct.has_error()) << direct.geterror();
    expect_same_channels(first, direct);
    int changed = 0;
    for (int y = 0; y < kCliHeight; ++y)
        for (int x = 0; x < kCliWidth; ++x)
            changed += first.getchannel(x, y, 0, 0) != frame.getchannel(x, y, 0, 0);
    EXPECT_GT(changed, kCliWidth * kCliHeight / 2);

    const CliResult r = run_cli(
        {dir.file("frame.exr"), "--dup", "--oidn", "--verify", "-o", dir.file("verified.exr")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const VerifyOptions defaults;
    const OIIO::ImageBuf want = verify(frame, first, defaults);
    ASSERT_FALSE(want.has_error()) << want.geterror();
    expect_same_channels(read_exr(dir.file("verified.exr")), want);
}

}  // namespace
}  // namespace statmc::test
