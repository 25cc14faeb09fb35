// statmc runs that succeed: outputs equal the operators' results on the same files.
#include <algorithm>
#include <array>
#include <filesystem>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "cli_images.h"
#include "cli_runner.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/passes/passes.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

void expect_success(const CliResult& r)
{
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_FALSE(r.timed_out);
}

TEST(CliRun, TheHeaderSaysHowTheImageWasDenoised)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("in.exr"));
    expect_success(run_cli({dir.file("in.exr"), "--denoise:alpha=0.01:radius=6:guides=albedo", "-o",
                            dir.file("out.exr")}));
    const OIIO::ImageSpec spec = read_exr(dir.file("out.exr")).spec();
    // Every parameter in force, in the parameter table's order, the method first.
    const std::string settings = spec.get_string_attribute("statmc:denoise");
    EXPECT_EQ(settings.rfind("method=default:radius=6:alpha=0.01:", 0), 0u) << settings;
    EXPECT_NE(settings.find(":guides=albedo:"), std::string::npos) << settings;
    const CliResult version = run_cli({"--version"});
    EXPECT_EQ("statmc " + std::string(spec.get_string_attribute("statmc:version")) + "\n",
              version.out);
    const CliResult info = run_cli({"--info", "-v", dir.file("out.exr")});
    EXPECT_NE(info.out.find(settings), std::string::npos) << info.out;
    // The record is a modifier string: given back to --denoise it makes the same image.
    expect_success(
        run_cli({dir.file("in.exr"), "--denoise:" + settings, "-o", dir.file("again.exr")}));
    expect_same_channels(read_exr(dir.file("again.exr")), read_exr(dir.file("out.exr")));
}

TEST(CliRun, DenoiseRoundTripEqualsTheOperator)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("in.exr"));
    const CliResult r = run_cli(
        {dir.file("in.exr"), "--denoise:radius=6:alpha=0.01:sigma_albedo=0.05:guides=albedo,normal",
         "-o", dir.file("out.exr")});
    expect_success(r);
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"in.exr", "out.exr"}));

    DenoiseImageOptions opt;
    opt.filter.radius = 6;
    opt.filter.alpha = 0.01;
    opt.filter.sigma_albedo = 0.05f;
    opt.guides.albedo = opt.guides.normal = GuideUse::Required;
    const OIIO::ImageBuf in = read_exr(dir.file("in.exr"));
    const OIIO::ImageBuf expected = denoise(in, opt);
    ASSERT_FALSE(expected.has_error()) << expected.geterror();
    const OIIO::ImageBuf out = read_exr(dir.file("out.exr"));
    expect_same_channels(out, expected);  // R,G,B denoised, every other channel kept
    EXPECT_EQ(out.spec().nchannels, in.spec().nchannels);
    EXPECT_EQ(out.spec().get_int_attribute("statmc:denoised"), 1);
    EXPECT_EQ(out.spec().get_int_attribute("statmc:spp"), 8);
    EXPECT_EQ(out.spec().get_string_attribute("compression"), "zip");
    // The denoiser changed the image.
    EXPECT_NE(channel_value(out, "R", 5, 5), channel_value(in, "R", 5, 5));
}

TEST(CliRun, DefaultsAndExplicitInputCommand)
{
    TempDir dir;
    write_exr(cli_variance_aov_image(), dir.file("aov.exr"));
    const CliResult r =
        run_cli({"-i", dir.file("aov.exr"), "--denoise", "-o", dir.file("out.exr")});
    // A variance AOV without M4 feeds the default's radius ladder as it is: nothing is left
    // out, and nothing is said.
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    const OIIO::ImageBuf expected = denoise(read_exr(dir.file("aov.exr")), DenoiseImageOptions{});
    const OIIO::ImageBuf out = read_exr(dir.file("out.exr"));
    expect_same_channels(out, expected);
    EXPECT_EQ(out.spec().get_string_attribute("statmc:denoiseSkipped"), "");
}

TEST(CliRun, OutputMayReplaceTheInput)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    const OIIO::ImageBuf expected = denoise(read_exr(dir.file("frame.exr")), DenoiseImageOptions{});
    expect_success(run_cli({dir.file("frame.exr"), "--denoise", "-o", dir.file("frame.exr")}));
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"frame.exr"}));
    expect_same_channels(read_exr(dir.file("frame.exr")), expected);
}

TEST(CliRun, DisplayedPicturesGoToPngJpegAndTiff)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    expect_success(
        run_cli({dir.file("frame.exr"), "--denoise", "--display", "-o", dir.file("shown.exr")}));
    const OIIO::ImageBuf exr = read_exr(dir.file("shown.exr"));
    for (const char* name : {"shown.png", "shown.tif", "shown.jpg"}) {
        expect_success(
            run_cli({dir.file("frame.exr"), "--denoise", "--display", "-o", dir.file(name)}));
        OIIO::ImageBuf picture(dir.file(name));
        ASSERT_TRUE(picture.read(0, 0, true, OIIO::TypeFloat)) << name;
        ASSERT_EQ(picture.spec().width, exr.spec().width) << name;
        // The same picture, as the format quantizes it (JPEG also compresses it).
        const float tolerance =
            std::string(name).find(".jpg") != std::string::npos ? 0.08f : 0.003f;
        for (int y = 0; y < exr.spec().height; y += 3)
            for (int x = 0; x < exr.spec().width; x += 3)
                ASSERT_NEAR(picture.getchannel(x, y, 0, 1), exr.getchannel(x, y, 0, 1), tolerance)
                    << name << " at (" << x << ", " << y << ")";
    }
}

TEST(CliRun, ValidateRunsNothing)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("in.exr"));
    const CliResult r = run_cli(
        {dir.file("in.exr"), "--denoise:radius=4", "-o", dir.file("out.exr"), "--validate"});
    expect_success(r);
    EXPECT_EQ(r.out, "statmc: the command line is valid\n");
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"in.exr"}));
}

TEST(CliRun, DenoisingADenoisedFileWarnsNamingIt)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    expect_success(run_cli({dir.file("frame.exr"), "--denoise", "-o", dir.file("once.exr")}));
    const CliResult again =
        run_cli({dir.file("once.exr"), "--denoise", "-o", dir.file("twice.exr")});
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(again.err, "--denoise: warning: " + dir.file("once.exr") +
                             ": beauty denoised already (statmc:denoisedLayers = beauty): what "
                             "was denoised is no longer its samples' mean; denoise the "
                             "statistics it came from\n");
}

TEST(CliRun, DenoisingAnotherLayerOfADenoisedFileIsNotWarnedAbout)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("frame.exr"));
    expect_success(run_cli({dir.file("frame.exr"), "--ch",
                            "R,G,B,variance.R,variance.G,variance.B,sampleCount.Y,"
                            "diffuse.R=R,diffuse.G=G,diffuse.B=B,diffuse.variance.R=variance.R,"
                            "diffuse.variance.G=variance.G,diffuse.variance.B=variance.B",
                            "-o", dir.file("aovs.exr")}));
    // One AOV after the other, as README's recipe does: the second is as rendered.
    expect_success(run_cli(
        {dir.file("aovs.exr"), "--denoise", "--denoise:aov=diffuse", "-o", dir.file("both.exr")}));
    const CliResult again =
        run_cli({dir.file("both.exr"), "--denoise:aov=diffuse", "-o", dir.file("again.exr")});
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.err.find("diffuse denoised already (statmc:denoisedLayers = beauty,diffuse)"),
              std::string::npos)
        << again.err;
}

// A tiled RGB MIP map of `levels` levels from 32x32 down, level m filled with m + 0.5.
void write_mip_map(const std::string& path, int levels)
{
    OIIO::ImageSpec spec(32, 32, 3, OIIO::TypeDesc::HALF);
    spec.tile_width = spec.tile_height = 16;
    spec.attribute("textureformat", "Plain Texture");
    auto out = OIIO::ImageOutput::create(path);
    for (int m = 0; m < levels; ++m) {
        OIIO::ImageSpec level = spec;
        level.width = level.height = level.full_width = level.full_height = 32 >> m;
        OIIO::ImageBuf buf(level);
        OIIO::ImageBufAlgo::fill(buf, {m + 0.5f, m + 0.5f, m + 0.5f});
        ASSERT_TRUE(out->open(
            path, level, m == 0 ? OIIO::ImageOutput::Create : OIIO::ImageOutput::AppendMIPLevel))
            << out->geterror();
        ASSERT_TRUE(buf.write(out.get())) << buf.geterror();
    }
    ASSERT_TRUE(out->close());
}

// Each MIP level of subimage 0 of `path`: {width, channels, value of its first pixel}.
std::vector<std::array<float, 3>> mip_levels_of(const std::string& path)
{
    std::vector<std::array<float, 3>> levels;
    auto in = OIIO::ImageInput::open(path);
    for (int m = 0; in && in->seek_subimage(0, m); ++m) {
        std::vector<float> pixels(std::size_t(in->spec().image_pixels()) *
                                  std::size_t(in->spec().nchannels));
        in->read_image(0, m, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
        levels.push_back({float(in->spec().width), float(in->spec().nchannels), pixels[0]});
    }
    return levels;
}

TEST(CliRun, CopiesKeepMipLevels)
{
    TempDir dir;
    const std::string in = dir.file("mip.exr");
    write_mip_map(in, 6);
    const auto want = mip_levels_of(in);
    ASSERT_EQ(want.size(), 6u);
    expect_success(run_cli({in, "-o", dir.file("copy.exr")}));
    EXPECT_EQ(mip_levels_of(dir.file("copy.exr")), want);
    expect_success(run_cli({in, "--subimage", "0", "-o", dir.file("sub.exr")}));
    EXPECT_EQ(mip_levels_of(dir.file("sub.exr")), want);
    // A channel selection applies to every level.
    expect_success(run_cli({"-i:ch=R,G", in, "-o", dir.file("rg.exr")}));
    const auto rg = mip_levels_of(dir.file("rg.exr"));
    ASSERT_EQ(rg.size(), 6u);
    for (int m = 0; m < 6; ++m)
        EXPECT_EQ(rg[std::size_t(m)], (std::array<float, 3>{float(32 >> m), 2.f, m + 0.5f}));
    // Parts joined and deleted keep the levels of the parts they keep; a multi-part file
    // with MIP levels cannot be written (OIIO 2.4), and says so rather than drop them.
    const CliResult two = run_cli({in, in, "--siappend", "-o", dir.file("two.exr")});
    EXPECT_EQ(two.exit_code, 1);
    EXPECT_NE(two.err.find("subimage 0 has 6 MIP levels, which statmc cannot write into a "
                           "multi-part file"),
              std::string::npos)
        << two.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("two.exr")));
    expect_success(
        run_cli({in, in, "--siappend", "--subimage:delete=1", "0", "-o", dir.file("one.exr")}));
    EXPECT_EQ(mip_levels_of(dir.file("one.exr")), want);
    // An operator's result is one level, as in oiiotool.
    expect_success(run_cli({in, "--mulc", "2", "-o", dir.file("twice.exr")}));
    EXPECT_EQ(mip_levels_of(dir.file("twice.exr")).size(), 1u);
}

// cli_render(k) written as Blender writes a multilayer EXR (ViewLayer.Combined.R, ...,
// ViewLayer.Denoising Albedo.R, ...).
OIIO::ImageBuf blender_render(int k)
{
    const OIIO::ImageBuf plain = cli_render(k);
    std::vector<std::string> names;
    for (const std::string& name : plain.spec().channelnames)
        names.push_back(name.size() == 1 ? "ViewLayer.Combined." + name
                                         : "ViewLayer.Denoising Albedo." + name.substr(7));
    std::vector<int> order(names.size());
    for (std::size_t c = 0; c < order.size(); ++c)
        order[c] = int(c);
    OIIO::ImageBuf out = OIIO::ImageBufAlgo::channels(plain, int(order.size()), order, {}, names);
    out.specmod().attribute("cycles.ViewLayer.samples", "8");
    return out;
}

TEST(CliRun, BlenderMultilayerPassesDenoiseAsPlainOnes)
{
    TempDir dir;
    std::vector<std::string> plain, blender;
    for (int k = 0; k < 3; ++k) {
        plain.push_back(dir.file("r" + std::to_string(k) + ".exr"));
        blender.push_back(dir.file("ml" + std::to_string(k) + ".exr"));
        write_exr(cli_render(k), plain.back());
        write_exr(blender_render(k), blender.back());
    }
    auto run = [&](std::vector<std::string> args, const std::string& out) {
        for (const char* a : {"--passes", "--denoise:radius=4", "-o"})
            args.push_back(a);
        args.push_back(out);
        expect_success(run_cli(args));
        return read_exr(out);
    };
    const OIIO::ImageBuf want = run(plain, dir.file("plain.exr"));
    const OIIO::ImageBuf got = run(blender, dir.file("blender.exr"));
    expect_same_channels(got, want);

    const CliResult info = run_cli({"--info", "-v", blender[0]});
    expect_success(info);
    EXPECT_NE(info.out.find("    statmc preset: cycles (channel ViewLayer.Combined.R)\n"),
              std::string::npos)
        << info.out;
    // A plain render names what to do.
    const CliResult plain_denoise = run_cli({plain[0], "--denoise", "-o", dir.file("x.exr")});
    EXPECT_EQ(plain_denoise.exit_code, 1);
    EXPECT_NE(plain_denoise.err.find("--passes --denoise -o out.exr"), std::string::npos)
        << plain_denoise.err;
    EXPECT_NE(plain_denoise.err.find("name its preset (--denoise:from=renderman, pbrt-v4"),
              std::string::npos)
        << plain_denoise.err;
}

TEST(CliRun, OutputKeepMeansDropsTheStatistics)
{
    TempDir dir;
    const std::string in = dir.file("stats.exr"), out = dir.file("comp.exr");
    write_exr(cli_statistics_image(), in);
    expect_success(run_cli({in, "--denoise:radius=3", "-o:keep=means", out}));
    const OIIO::ImageBuf kept = read_exr(out), full = read_exr(in);
    for (const std::string& name : full.spec().channelnames) {
        // The image's means are the beauty's R,G,B; its other layers are guides.
        const bool mean_or_guide = name.find('.') == std::string::npos ||
                                   name.rfind("albedo.", 0) == 0 || name.rfind("normal.", 0) == 0 ||
                                   name.rfind("depth.", 0) == 0;
        EXPECT_EQ(kept.spec().channelindex(name) >= 0, mean_or_guide) << name;
    }
    EXPECT_GE(kept.spec().channelindex("R"), 0);
}

TEST(CliRun, PassesThenDenoise)
{
    TempDir dir;
    for (int k = 0; k < 3; ++k)
        write_exr(cli_render(k), dir.file("r" + std::to_string(k) + ".exr"));
    expect_success(run_cli({dir.file("r0.exr"), dir.file("r1.exr"), dir.file("r2.exr"), "--passes",
                            "-o", dir.file("stats.exr")}));
    expect_success(run_cli({dir.file("r0.exr"), dir.file("r1.exr"), dir.file("r2.exr"), "--passes",
                            "--denoise:radius=4", "-o", dir.file("out.exr")}));

    const OIIO::ImageBuf r0 = read_exr(dir.file("r0.exr")), r1 = read_exr(dir.file("r1.exr")),
                         r2 = read_exr(dir.file("r2.exr"));
    const OIIO::ImageBuf stats = passes({&r0, &r1, &r2});
    ASSERT_FALSE(stats.has_error()) << stats.geterror();
    const OIIO::ImageBuf stats_file = read_exr(dir.file("stats.exr"));
    expect_same_channels(stats_file, stats);
    EXPECT_EQ(channel_value(stats_file, "sampleCount.Y", 0, 0), 3.f);
    // Hand check of one pixel: R at (1, 1) over k = 0, 1, 2.
    double v[3], mean = 0;
    for (int k = 0; k < 3; ++k)
        mean += v[k] = 0.2f + 0.1f * float((5 + 3 + k * 7) % 5);
    mean /= 3;
    double var = 0;
    for (double x : v)
        var += (x - mean) * (x - mean);
    EXPECT_FLOAT_EQ(channel_value(stats_file, "R", 1, 1), float(mean));
    EXPECT_FLOAT_EQ(channel_value(stats_file, "variance.R", 1, 1), float(var / 2));

    DenoiseImageOptions opt;
    opt.filter.radius = 4;
    expect_same_channels(read_exr(dir.file("out.exr")), denoise(stats, opt));
}

TEST(CliRun, PassesTakesTheTopNImages)
{
    TempDir dir;
    for (int k = 0; k < 3; ++k)
        write_exr(cli_render(k), dir.file("r" + std::to_string(k) + ".exr"));
    expect_success(run_cli({dir.file("r0.exr"), dir.file("r1.exr"), dir.file("r2.exr"),
                            "--passes:n=2", "-o", dir.file("stats.exr")}));
    const OIIO::ImageBuf r1 = read_exr(dir.file("r1.exr")), r2 = read_exr(dir.file("r2.exr"));
    const OIIO::ImageBuf stats_file = read_exr(dir.file("stats.exr"));
    EXPECT_EQ(channel_value(stats_file, "sampleCount.Y", 3, 3), 2.f);
    expect_same_channels(stats_file, passes({&r1, &r2}));
}

TEST(CliRun, ThreadsDoNotChangeTheResult)
{
    TempDir dir;
    write_exr(cli_statistics_image(), dir.file("in.exr"));
    expect_success(
        run_cli({"--threads", "1", dir.file("in.exr"), "--denoise", "-o", dir.file("one.exr")}));
    expect_success(
        run_cli({"--threads", "0", dir.file("in.exr"), "--denoise", "-o", dir.file("all.exr")}));
    expect_same_channels(read_exr(dir.file("one.exr")), read_exr(dir.file("all.exr")));
}

TEST(CliRun, DenoiseAovWithDiagnostics)
{
    TempDir dir;
    layers::StatisticsMetadata meta;
    meta.aov = "diffuse";
    write_exr(layers::make_statistics_image(noisy_statistics(kCliWidth, kCliHeight, 8, 5), meta),
              dir.file("aov.exr"));
    // Diagnostics describe one radius per pixel: the classic filter's.
    expect_success(
        run_cli({dir.file("aov.exr"), "--denoise:method=classic:aov=diffuse:radius=4:diagnostics=1",
                 "-o", dir.file("out.exr")}));
    DenoiseImageOptions opt = DenoiseImageOptions::classic();
    opt.aov = "diffuse";
    opt.filter.radius = 4;
    opt.diagnostics = true;
    const OIIO::ImageBuf expected = denoise(read_exr(dir.file("aov.exr")), opt);
    ASSERT_FALSE(expected.has_error()) << expected.geterror();
    const OIIO::ImageBuf out = read_exr(dir.file("out.exr"));
    expect_same_channels(out, expected);
    EXPECT_GE(out.spec().channelindex("diffuse.diagnostics.members"), 0);
    EXPECT_GE(out.spec().channelindex("diffuse.diagnostics.effectiveSamples"), 0);
    // Somewhere the filter averaged more than the pixel itself.
    float most = 0;
    for (int y = 0; y < kCliHeight; ++y)
        for (int x = 0; x < kCliWidth; ++x)
            most = std::max(most, channel_value(out, "diffuse.diagnostics.members", x, y));
    EXPECT_GT(most, 1.f);
}

TEST(CliRun, HelpListsEveryCommandAndModifier)
{
    const CliResult r = run_cli({"--help"});
    expect_success(r);
    for (const char* text :
         {"-i[:mod=val...] FILE", "-o[:mod=val...] FILE", "--denoise", "--passes", "--threads N",
          "--help", "--version", ":radius=20 ", ":alpha=0.005 ", ":sigma_albedo=0.02 ",
          ":sigma_normal=0.1 ", ":guides=auto ", "(albedo,normal|auto|none)", ":test=auto ",
          "(auto|boxcox|untransformed)", ":nonfinite=error ", "(error|zero)", ":n=int ",
          ":diagnostics=0 ", ":aov=name ", ":aovs=name,name,... ",
          // the oiiotool commands, from the same table
          "-d TYPE", "--compression NAME", "-a ", "--ch[:mod=val...] CHANLIST",
          "--chnames[:mod=val...] NAMELIST", "--chappend", "--subimage[:mod=val...] N|NAME",
          "--siappend", "--add", "--sub", "--mul", "--addc[:mod=val...] VAL",
          "--mulc[:mod=val...] VAL", "--colorconfig FILE", "--colorconvert[:mod=val...] FROM TO",
          "--ociodisplay[:mod=val...] DISPLAY VIEW", "--crop[:mod=val...] GEOM",
          "--resize[:mod=val...] GEOM", ":filter=name ", "--info", "-v ", "--stats", "--diff",
          "--echo[:mod=val...] TEXT", ":subimages=name "})
        EXPECT_NE(r.out.find(text), std::string::npos) << text;
    EXPECT_EQ(run_cli({"-h"}).out, r.out);
    EXPECT_EQ(run_cli({}).out, r.out);
}

TEST(CliRun, Version)
{
    const CliResult r = run_cli({"--version"});
    expect_success(r);
    EXPECT_EQ(r.out.rfind("statmc ", 0), 0u);
}

}  // namespace
}  // namespace statmc::test
