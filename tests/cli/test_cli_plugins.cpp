// Plugins seen from the command line: the shipped operators listed and described from
// their registrations, a module found on STATMC_PLUGIN_PATH, a module refused.
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/layer_names.h"

#include "cli_images.h"
#include "cli_runner.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

const std::string kModules = STATMC_TEST_MODULE_DIR;

// Sets STATMC_PLUGIN_PATH for the statmc processes this test starts.
class PluginPath {
public:
    explicit PluginPath(const std::string& path) { setenv("STATMC_PLUGIN_PATH", path.c_str(), 1); }
    ~PluginPath() { unsetenv("STATMC_PLUGIN_PATH"); }
};

TEST(CliPlugins, ListsTheShippedOperators)
{
    const CliResult r = run_cli({"--list-ops"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("--denoise     1 image"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("--passes      2+ renders"), std::string::npos) << r.out;
}

// Runs of spaces as one: the table's columns are as wide as its longest entry.
std::string squeezed(const std::string& text)
{
    std::string out;
    for (char c : text)
        if (!(c == ' ' && !out.empty() && out.back() == ' '))
            out.push_back(c);
    return out;
}

TEST(CliPlugins, HelpOfAnOperatorIsItsParameterTable)
{
    const CliResult r = run_cli({"--help", "denoise"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string table = squeezed(r.out);
    for (const char* row :
         {"\n parameter type default range meaning\n", "\n radius int 20 [0, 1000] ",
          "\n alpha float 0.005 (0, 1) ", "\n sigma_albedo float 0.02 > 0 ",
          "\n test choice auto - ", "\n method choice default - ", "\n temporal int 0 [0, 16] ",
          "denoise.so"})
        EXPECT_NE(table.find(row), std::string::npos) << row << "\n" << r.out;
    // The product's options only: a method's internal settings are not parameters.
    for (const char* internal :
         {"\n ici ", "\n context ", "\n guide_noise ", "\n variance_dof ", "\n sigma_s "})
        EXPECT_EQ(table.find(internal), std::string::npos) << internal << "\n" << r.out;
    EXPECT_EQ(run_cli({"--help", "--denoise"}).out, r.out);
    const CliResult unknown = run_cli({"--help", "denoize"});
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_NE(unknown.err.find("--help: unknown operator 'denoize'"), std::string::npos);
}

TEST(CliPlugins, ModuleOnThePluginPathRunsLikeAShippedOne)
{
    TempDir dir;
    write_exr(cli_render(0), dir.file("in.exr"));
    // The shipped directory named again is searched once, not refused as duplicates.
    PluginPath path("/nonexistent:" + kModules + "/good:" + kModules +
                    "/good/:" + std::string(STATMC_PLUGIN_DIR));
    const CliResult list = run_cli({"--list-ops"});
    EXPECT_NE(list.out.find("--testscale"), std::string::npos) << list.out << list.err;
    const CliResult help = run_cli({"--help", "testscale"});
    EXPECT_NE(help.out.find("factor      float   2         [0.01, 100]"), std::string::npos)
        << help.out;

    const CliResult run =
        run_cli({dir.file("in.exr"), "--testscale:factor=3", "-o", dir.file("out.exr")});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const OIIO::ImageBuf in = read_exr(dir.file("in.exr"));
    const OIIO::ImageBuf out = read_exr(dir.file("out.exr"));
    EXPECT_FLOAT_EQ(out.getchannel(5, 7, 0, 1), 3 * in.getchannel(5, 7, 0, 1));

    const CliResult bad =
        run_cli({dir.file("in.exr"), "--testscale:factor=500", "-o", dir.file("bad.exr")});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("--testscale: factor must be in [0.01, 100], got 500"),
              std::string::npos)
        << bad.err;
    const CliResult notbool =
        run_cli({dir.file("in.exr"), "--testscale:reciprocal=maybe", "-o", dir.file("bad.exr")});
    EXPECT_NE(notbool.err.find("--testscale: reciprocal: expected a boolean"), std::string::npos)
        << notbool.err;
}

TEST(CliPlugins, ModuleOfAnotherInterfaceVersionIsRefused)
{
    PluginPath path(kModules + "/wrong");
    const CliResult r = run_cli({"--list-ops"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.signal, 0);
    EXPECT_NE(r.err.find(kModules + "/wrong/wrong_version.so: plugin interface version"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("needs version"), std::string::npos) << r.err;
}

TEST(CliPlugins, ModuleBuiltAgainstAnotherOiioIsRefused)
{
    PluginPath path(kModules + "/wrong_identity");
    const CliResult r = run_cli({"--list-ops"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.signal, 0);  // refused before its registration (which aborts) is called
    const std::string module = kModules + "/wrong_identity/wrong_identity.so";
    EXPECT_NE(r.err.find(module + ": built differently from this statmc: OpenImageIO "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("sizeof(OIIO::ImageBuf) "), std::string::npos) << r.err;
}

TEST(CliPlugins, AnOperatorThatThrowsIsAnErrorNamingItsModule)
{
    TempDir dir;
    write_exr(cli_render(0), dir.file("in.exr"));
    PluginPath path(kModules + "/good");
    const std::string module = kModules + "/good/testscale.so";
    for (const std::string op : {"--testthrow", "--testthrowinplace"}) {
        const CliResult r = run_cli({dir.file("in.exr"), op, "-o", dir.file("out.exr")});
        EXPECT_EQ(r.exit_code, 1) << op;
        EXPECT_EQ(r.signal, 0) << op;
        EXPECT_NE(r.err.find("statmc: error: " + op + ": " + dir.file("in.exr") +
                             ": the operator threw, which it must not: deliberate failure [" + op +
                             " (" + module + ")]"),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
        const CliResult odd =
            run_cli({dir.file("in.exr"), op + ":not_std=1", "-o", dir.file("out.exr")});
        EXPECT_EQ(odd.exit_code, 1) << op;
        EXPECT_NE(odd.err.find("the operator threw a non-standard exception [" + op + " (" +
                               module + ")]"),
                  std::string::npos)
            << odd.err;
        EXPECT_FALSE(std::filesystem::exists(dir.file("out.exr"))) << op;
    }
}

TEST(CliPlugins, MergeAddsFarmTasksAndNamesMismatchedFiles)
{
    TempDir dir;
    const std::string a = dir.file("a.exr"), b = dir.file("b.exr"), c = dir.file("c.exr"),
                      v = dir.file("v.exr");
    // Three renders of the same statistics with different seeds (seed 77 draws samples 0..7).
    write_exr(cli_statistics_image(), a);
    for (const auto& [file, seed] : {std::pair{b, 78}, std::pair{c, 79}}) {
        OIIO::ImageBuf other = cli_statistics_image();
        other.specmod().attribute(layers::attr::kSeed, seed);
        write_exr(other, file);
    }
    write_exr(cli_variance_aov_image(), v);
    const CliResult r = run_cli({a, b, c, "--merge", "-o", dir.file("all.exr")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const OIIO::ImageBuf in = read_exr(a), all = read_exr(dir.file("all.exr"));
    EXPECT_EQ(channel_value(all, "sampleCount.Y", 3, 2),
              3 * channel_value(in, "sampleCount.Y", 3, 2));
    EXPECT_NEAR(channel_value(all, "G", 3, 2), channel_value(in, "G", 3, 2), 1e-5);
    // The same file twice: its samples would count twice.
    const CliResult twice = run_cli({a, b, a, "--merge", "-o", dir.file("twice.exr")});
    EXPECT_EQ(twice.exit_code, 1);
    EXPECT_NE(twice.err.find("--merge: part 0 (" + a + ": seed 77, samples 0..7) and part 2 (" + a +
                             ": seed 77, samples 0..7) drew the same samples"),
              std::string::npos)
        << twice.err;

    const CliResult n = run_cli({v, a, b, "--merge:n=2", "-o", dir.file("two.exr")});
    EXPECT_EQ(n.exit_code, 0) << n.err;
    const CliResult bad = run_cli({a, v, "--merge", "-o", dir.file("bad.exr")});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("--merge: part 1 (" + v + ") and part 0 (" + a + ") differ in"),
              std::string::npos)
        << bad.err;
    const CliResult denoised =
        run_cli({a, "--denoise:radius=1", b, "--merge", "-o", dir.file("bad.exr")});
    EXPECT_NE(denoised.err.find("is denoised (statmc:denoised=1)"), std::string::npos)
        << denoised.err;
}

TEST(CliPlugins, ComparePrintsMetricsAndPushesTheErrorImage)
{
    TempDir dir;
    const std::string a = dir.file("a.exr"), ref = dir.file("ref.exr");
    write_exr(cli_render(0), a);
    write_exr(cli_render(1), ref);
    const CliResult r =
        run_cli({a, ref, "--compare:errorimage=" + dir.file("e1.exr"), "-o", dir.file("e2.exr")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* row : {"RMSE", "MAE", "relMSE", "SSIM", "DSSIM"})
        EXPECT_NE(r.out.find("\n  " + std::string(row) + " "), std::string::npos) << r.out;
    const OIIO::ImageBuf e1 = read_exr(dir.file("e1.exr")), e2 = read_exr(dir.file("e2.exr"));
    const OIIO::ImageBuf x = read_exr(a), y = read_exr(ref);
    EXPECT_FLOAT_EQ(e2.getchannel(4, 5, 0, 1),
                    std::abs(x.getchannel(4, 5, 0, 1) - y.getchannel(4, 5, 0, 1)));
    EXPECT_EQ(e1.getchannel(4, 5, 0, 1), e2.getchannel(4, 5, 0, 1));
    const CliResult same = run_cli({a, a, "--compare"});
    EXPECT_NE(same.out.find("  RMSE    0\n"), std::string::npos) << same.out;
    EXPECT_NE(same.out.find("  SSIM    1\n"), std::string::npos) << same.out;
}

TEST(CliPlugins, DisplayUsesTheShippedConfigWithoutOcio)
{
    TempDir dir;
    const std::string in = dir.file("in.exr");
    write_exr(cli_render(0), in);
    unsetenv("OCIO");
    const CliResult r = run_cli({in, "--display", "-o", dir.file("srgb.exr")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const float linear = read_exr(in).getchannel(6, 3, 0, 1);
    const float encoded =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
    EXPECT_NEAR(read_exr(dir.file("srgb.exr")).getchannel(6, 3, 0, 1), encoded, 1e-4f);
    const CliResult bad = run_cli({in, "--display:view=Nope", "-o", dir.file("bad.exr")});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(
        bad.err.find("--display: " + in + ": view 'Nope' of display 'sRGB' is not in OCIO config "),
        std::string::npos)
        << bad.err;
    EXPECT_NE(bad.err.find("(views: sRGB, Filmic, Raw)"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace statmc::test
