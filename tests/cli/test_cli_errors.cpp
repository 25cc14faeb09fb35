// Every bad input ends in one "statmc: error: ..." line naming the culprit, exit code 1,
// no crash or hang, and no output or temporary file left behind.
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <thread>

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "cli_images.h"
#include "cli_runner.h"
#include "statmc/core/cuda_device.h"
#include "statmc/layers/statistics_layers.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

class CliError : public ::testing::Test {
protected:
    // Writes an input file and remembers it as one the directory may hold afterwards.
    std::string input(const std::string& name, const OIIO::ImageBuf& image)
    {
        write_exr(image, dir.file(name));
        inputs.push_back(name);
        return dir.file(name);
    }

    std::string text_input(const std::string& name, const std::string& content)
    {
        std::ofstream(dir.file(name)) << content;
        inputs.push_back(name);
        return dir.file(name);
    }

    std::string out() const { return dir.file("out.exr"); }

    // The run failed cleanly with `message` and left only the inputs.
    void expect_failure(const std::vector<std::string>& args, const std::string& message)
    {
        const CliResult r = run_cli(args);
        EXPECT_FALSE(r.timed_out);
        EXPECT_EQ(r.signal, 0) << "killed by signal " << r.signal;
        EXPECT_EQ(r.exit_code, 1) << r.err;
        EXPECT_EQ(r.err.rfind("statmc: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << "expected \"" << message << "\" in:\n"
                                                          << r.err;
        EXPECT_EQ(r.out, "");
        std::vector<std::string> expected = inputs;
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(dir.entries(), expected) << "stray output or temporary file";
    }

    TempDir dir;
    std::vector<std::string> inputs;
};

TEST_F(CliError, ReadLimitsAndChecks)
{
    const std::string in = input("in.exr", cli_statistics_image());
    expect_failure({"--max-memory", "1K", in, "-o", out()},
                   in + ": subimage 0 declares 24x16 pixels x 32 channels, 49.2 KB as float, more "
                        "than the 1 KB one image may take (--max-memory)");
    expect_failure({"--max-memory", "lots", in, "-o", out()},
                   "--max-memory: expected a size such as 16G, 512M or a byte count, got 'lots'");
    expect_failure({"--check-inputs", "yes", in, "-o", out()},
                   "--check-inputs: expected 0 or 1, got 'yes'");
    const std::string bytes = file_bytes(in);
    const std::string cut = text_input("cut.exr", bytes.substr(0, bytes.size() / 2));
    expect_failure({cut, "-o", out()}, cut + ": damaged OpenEXR file");
    expect_failure({"--check-inputs", "0", cut, "-o", out()}, cut + ": ");
    const CliResult ok = run_cli({"--max-memory", "1G", "--check-inputs", "0", in, "-o", out()});
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST_F(CliError, MissingLayer)
{
    const auto in = input("in.exr", without_channels(cli_variance_aov_image(),
                                                     {"variance.R", "variance.G", "variance.B"}));
    expect_failure({in, "--denoise", "-o", out()},
                   "--denoise: " + in +
                       ": missing layer variance (channels variance.R, variance.G, variance.B)");
}

TEST_F(CliError, MissingSampleCount)
{
    const auto in = input("in.exr", without_channels(cli_statistics_image(), {"sampleCount.Y"}));
    expect_failure({in, "--denoise", "-o", out()},
                   in + ": missing layer sampleCount (channels sampleCount.Y)");
}

TEST_F(CliError, MisnamedLayer)
{
    const auto in =
        input("in.exr", renamed_channels(cli_variance_aov_image(), "variance", "Variance"));
    expect_failure({in, "--denoise", "-o", out()},
                   "missing layer variance (channels variance.R, variance.G, variance.B); "
                   "denoising needs it or the Box-Cox layers (boxcoxMean, boxcoxVariance, "
                   "boxcoxM3); the image has layers R,G,B, Variance, sampleCount; did you "
                   "mean Variance?");
}

TEST_F(CliError, MissingRequestedGuide)
{
    const auto in = input(
        "in.exr", without_channels(cli_statistics_image(), {"normal.X", "normal.Y", "normal.Z"}));
    expect_failure({in, "--denoise:guides=albedo,normal", "-o", out()},
                   in + ": missing guide layer normal (channels normal.X, normal.Y, normal.Z)");
}

TEST_F(CliError, PassesWithMismatchedResolutions)
{
    const auto a = input("a.exr", cli_render(0));
    const auto b = input("b.exr", cli_render(1, kCliWidth, kCliHeight - 2));
    expect_failure({a, b, "--passes", "-o", out()}, "--passes: render 1 (" + b +
                                                        ") and render 0 (" + a +
                                                        ") differ in resolution: 24x14 vs 24x16");
}

TEST_F(CliError, PassesWithMismatchedDataWindows)
{
    const auto a = input("a.exr", cli_render(0));
    OIIO::ImageBuf moved = cli_render(1);
    moved.set_origin(2, 3);
    const auto b = input("b.exr", moved);
    expect_failure({a, b, "--passes", "-o", out()},
                   "render 1 (" + b + ") and render 0 (" + a +
                       ") differ in data window: origin (2, 3) vs (0, 0)");
}

TEST_F(CliError, PassesWithMismatchedChannels)
{
    const auto a = input("a.exr", cli_render(0));
    const auto b =
        input("b.exr", without_channels(cli_render(1), {"albedo.R", "albedo.G", "albedo.B"}));
    expect_failure({a, b, "--passes", "-o", out()},
                   "render 1 (" + b + ") and render 0 (" + a + ") differ in channels");
}

TEST_F(CliError, PassesNeedsTwoRenders)
{
    const auto a = input("a.exr", cli_render(0));
    expect_failure({a, "--passes", "-o", out()}, "--passes: needs at least 2 renders, got 1");
    expect_failure({a, a, "--passes:n=3", "-o", out()},
                   "--passes: needs 3 images, the stack holds 2");
    expect_failure({a, a, "--passes:n=1", "-o", out()}, "--passes: n must be at least 2, got 1");
}

TEST_F(CliError, PassesOfOneSeedAreRefusedAndWriteNothing)
{
    // Blender renders a frame K times identically unless each pass gets its own seed; the
    // same file twice is the same mistake.
    const auto a = input("a.exr", cli_render(0));
    const auto b = input("b.exr", cli_render(0));
    const auto c = input("c.exr", cli_render(1));
    const std::string message =
        " hold the same pixels: they were rendered with one seed, so they are one sample, not "
        "two. Render each pass with its own seed (Blender: Render Properties > Sampling > "
        "Advanced > Seed";
    expect_failure({a, a, "--passes", "--denoise", "-o", out()},
                   "--passes: render 1 (" + a + ") and render 0 (" + a + ")" + message);
    expect_failure({c, a, b, "--passes", "-o", out()},
                   "--passes: render 2 (" + b + ") and render 1 (" + a + ")" + message);
}

TEST_F(CliError, ValidateChecksTheCommandsBeforeItAndMustComeLast)
{
    const auto in = input("in.exr", cli_statistics_image());
    expect_failure({in, "--denoise:radious=2", "-o", out(), "--validate"}, "radious");
    expect_failure({"--validate", in, "--denoise:radious=2"},
                   "--validate checks the commands before it: put it last, not before '" + in +
                       "'");
}

TEST_F(CliError, NegativeVariance)
{
    OIIO::ImageBuf img = cli_variance_aov_image();
    set_channel(img, "variance.G", 12, 7, -0.3f);
    const auto in = input("in.exr", img);
    expect_failure({in, "--denoise", "-o", out()},
                   in + ": variance.G: negative value -0.3 at pixel (12, 7) [1 pixel affected]");
}

TEST_F(CliError, ZeroSampleCount)
{
    OIIO::ImageBuf img = cli_statistics_image();
    set_channel(img, "sampleCount.Y", 3, 4, 0.f);
    const auto in = input("in.exr", img);
    expect_failure({in, "--denoise:nonfinite=zero", "-o", out()},
                   "sampleCount.Y: n = 0 at pixel (3, 4)");
}

TEST_F(CliError, NaNAndInfWithNonfiniteError)
{
    OIIO::ImageBuf nan = cli_statistics_image();
    set_channel(nan, "boxcoxMean.R", 9, 2, std::numeric_limits<float>::quiet_NaN());
    const auto a = input("nan.exr", nan);
    expect_failure({a, "--denoise", "-o", out()}, "boxcoxMean.R: NaN at pixel (9, 2)");

    OIIO::ImageBuf inf = cli_variance_aov_image();
    set_channel(inf, "R", 1, 0, std::numeric_limits<float>::infinity());
    const auto b = input("inf.exr", inf);
    expect_failure({b, "--denoise:nonfinite=error", "-o", out()}, "R: Inf at pixel (1, 0)");

    // The same files pass when non-finite values are zeroed.
    const CliResult ok = run_cli({a, "--denoise:nonfinite=zero", "-o", out()});
    EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST_F(CliError, TruncatedExr)
{
    const auto in = input("in.exr", cli_statistics_image());
    const auto size = std::filesystem::file_size(in);
    std::filesystem::resize_file(in, size - size / 3);
    expect_failure({in, "--denoise", "-o", out()}, in + ": damaged OpenEXR file: ");
    expect_failure({"--check-inputs", "0", in, "--denoise", "-o", out()},
                   in + ": not an OpenEXR/readable image: ");
    std::filesystem::resize_file(in, 64);  // cut inside the header
    expect_failure({in, "--denoise", "-o", out()}, in + ": not an OpenEXR/readable image: ");
}

TEST_F(CliError, DeviceCudaRunsOrSaysWhyAndWritesNothing)
{
    const auto in = input("in.exr", cli_statistics_image());
    std::string why;
    if (statmc::cuda_available(&why)) {  // a GPU is here: device=cuda runs on it
        const CliResult gpu = run_cli({in, "--denoise:device=cuda", "-o", out()});
        EXPECT_EQ(gpu.exit_code, 0) << gpu.err;
        return;
    }
    expect_failure({in, "--denoise:device=cuda", "-o", out()},
                   "--denoise: " + in + ": device=cuda: " + why);
    // auto takes the CPU, and gives the CPU's image.
    const CliResult cpu = run_cli({in, "--denoise", "-o", dir.file("cpu.exr")});
    const CliResult automatic = run_cli({in, "--denoise:device=auto", "-o", dir.file("auto.exr")});
    ASSERT_EQ(cpu.exit_code, 0) << cpu.err;
    ASSERT_EQ(automatic.exit_code, 0) << automatic.err;
    const CliResult same = run_cli({dir.file("cpu.exr"), dir.file("auto.exr"), "--compare"});
    EXPECT_NE(same.out.find("  RMSE    0\n"), std::string::npos) << same.out;
}

TEST_F(CliError, TextFileIsNotAnImage)
{
    const auto exr = text_input("notes.exr", "not an image\n");
    expect_failure({exr, "-o", out()}, exr + ": not an OpenEXR/readable image: ");
    const auto txt = text_input("notes.txt", "not an image either\n");
    expect_failure({txt, "-o", out()}, txt + ": not an OpenEXR/readable image: ");
}

TEST_F(CliError, NonexistentInput)
{
    const std::string missing = dir.file("missing.exr");
    expect_failure({missing, "--denoise", "-o", out()}, missing + ": no such file");
    expect_failure({"-i", dir.path().string(), "-o", out()}, ": is a directory, not a file");
    // A device would be read without end.
    expect_failure({"/dev/zero", "-o", out()},
                   "/dev/zero: is not a regular file (a device, pipe or socket)");
}

TEST_F(CliError, UnwritableOutput)
{
    const auto in = input("in.exr", cli_statistics_image());
    const std::string target = dir.file("no/such/dir/out.exr");
    expect_failure({in, "--denoise", "-o", target}, target + ": cannot write: directory '" +
                                                        dir.file("no/such/dir") +
                                                        "' does not exist");
    expect_failure({in, "-o", dir.file("out.png")},
                   "out.png: cannot write: the image holds statistics (");
    expect_failure({in, "-o", dir.file("out.png")},
                   "), which statmc writes as OpenEXR only (use the .exr extension); for a "
                   "picture, --display it first");
    expect_failure({in, "-o", dir.path().string()}, ": cannot write: it is a directory");
}

// A write that runs out of space: the previous output keeps its bytes, no temporary is
// left, and the message names the output and the system's reason.
void expect_kept_after_full_disk(const CliResult& r, const std::string& target,
                                 const std::string& reason)
{
    EXPECT_FALSE(r.timed_out);
    EXPECT_EQ(r.signal, 0) << "killed by signal " << r.signal;
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err.rfind("statmc: error: " + target + ": cannot write: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
    EXPECT_EQ(file_bytes(target), "the previous output");
    const std::filesystem::path dir = std::filesystem::path(target).parent_path();
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".statmc-tmp-"), std::string::npos)
            << "temporary left: " << entry.path();
}

TEST_F(CliError, AFullDiskKeepsThePreviousOutput)
{
    // About 750 KB of output: more than either limit below leaves room for.
    const std::string in = input(
        "big.exr", layers::make_statistics_image(noisy_statistics(128, 96, 8, 5), {"", 8, 5}));
    const std::string target = out();
    std::ofstream(target) << "the previous output";
    inputs.push_back("out.exr");

    // The write limit of the process (RLIMIT_FSIZE, with SIGXFSZ ignored so that the write
    // fails instead of the process): a full disk as the writer sees it, on any machine.
    const CliResult limited =
        run_program("/bin/sh", {"-c", "trap '' XFSZ; ulimit -f 64; exec \"$0\" \"$@\"",
                                STATMC_CLI_PATH, in, "-o", target});
    expect_kept_after_full_disk(limited, target, "File too large");

    // A real full file system: a 256 KB tmpfs, where this machine lets the test mount one.
    const std::string small = dir.file("small");
    std::filesystem::create_directory(small);
    inputs.push_back("small");
    if (::mount("tmpfs", small.c_str(), "tmpfs", 0, "size=256k") != 0) {
        std::cout << "tmpfs not mounted (" << std::strerror(errno)
                  << "): the full disk was tested through the write limit only\n";
        return;
    }
    const std::string on_tmpfs = small + "/out.exr";
    std::ofstream(on_tmpfs) << "the previous output";
    const CliResult full = run_cli({in, "-o", on_tmpfs});
    expect_kept_after_full_disk(full, on_tmpfs, "No space left on device");
    EXPECT_EQ(::umount2(small.c_str(), MNT_DETACH), 0) << std::strerror(errno);
}

TEST_F(CliError, OutOfRangeParameters)
{
    const auto in = input("in.exr", cli_statistics_image());
    expect_failure({in, "--denoise:radius=-1", "-o", out()},
                   "--denoise: radius must be in [0, 1000], got -1");
    expect_failure({in, "--denoise:radius=1001", "-o", out()},
                   "--denoise: radius must be in [0, 1000], got 1001");
    expect_failure({in, "--denoise:alpha=0", "-o", out()}, "--denoise: alpha must be in (0, 1)");
    expect_failure({in, "--denoise:alpha=1", "-o", out()}, "--denoise: alpha must be in (0, 1)");
    expect_failure({in, "--denoise:sigma_albedo=-2", "-o", out()},
                   "--denoise: sigma_albedo must be > 0");
    expect_failure({in, "--denoise:sigma_normal=0", "-o", out()},
                   "--denoise: sigma_normal must be > 0");
    expect_failure({"--threads", "-2", in, "-o", out()},
                   "--threads: thread count must be in [0, 4096], got -2");
}

TEST_F(CliError, MalformedParameters)
{
    const auto in = input("in.exr", cli_statistics_image());
    expect_failure({in, "--denoise:radius=abc", "-o", out()},
                   "--denoise: radius: expected an integer, got 'abc'");
    expect_failure({in, "--denoise:radius=3.5", "-o", out()},
                   "--denoise: radius: expected an integer, got '3.5'");
    expect_failure({in, "--denoise:radius=", "-o", out()},
                   "--denoise: radius: expected an integer, got ''");
    expect_failure({in, "--denoise:alpha=0.01x", "-o", out()},
                   "--denoise: alpha: expected a finite number, got '0.01x'");
    expect_failure({in, "--denoise:alpha=nan", "-o", out()},
                   "--denoise: alpha: expected a finite number, got 'nan'");
    expect_failure({in, "--denoise:test=fast", "-o", out()},
                   "--denoise: test: expected one of auto, boxcox, untransformed, got 'fast'");
    expect_failure({in, "--denoise:guides=albedo,depth", "-o", out()},
                   "--denoise: guides: unknown item 'depth'");
    expect_failure({in, "--denoise:radius", "-o", out()},
                   "--denoise: modifier 'radius' is not of the form name=value");
    expect_failure({in, "--denoise:radius=3:radius=4", "-o", out()},
                   "--denoise: modifier 'radius' given twice");
    expect_failure({"--threads", "many", in, "-o", out()},
                   "--threads: expected an integer, got 'many'");
}

TEST_F(CliError, UnknownModifier)
{
    const auto in = input("in.exr", cli_statistics_image());
    expect_failure(
        {in, "--denoise:radius=3:sigma=2", "-o", out()},
        "--denoise: unknown modifier 'sigma' (modifiers: method, radius, alpha, sigma_albedo");
    expect_failure({in, "-o:compression=zip", out()},
                   "-o: unknown modifier 'compression' (modifiers: type, datatype, keep)");
    expect_failure({in, "--siappend:all=1", out()},
                   "--siappend: unknown modifier 'all' (modifiers: n)");
    expect_failure({in, in, "--chappend:n=1", out()}, "--chappend: n must be");
}

TEST_F(CliError, UnknownCommand)
{
    const auto in = input("in.exr", cli_statistics_image());
    expect_failure({in, "--denoize", "-o", out()}, "unknown command '--denoize'");
    // Checked before anything runs: the earlier -o writes nothing either.
    expect_failure({in, "-o", out(), "--bogus"}, "unknown command '--bogus'");
}

TEST_F(CliError, OutputWithEmptyStack)
{
    expect_failure({"-o", out()}, "-o: the image stack is empty");
    expect_failure({"--denoise", "-o", out()}, "--denoise: the image stack is empty");
}

TEST_F(CliError, MissingArguments)
{
    const auto in = input("in.exr", cli_statistics_image());
    expect_failure({in, "--denoise", "-o"}, "-o: missing argument FILE");
    expect_failure({in, "--threads"}, "--threads: missing argument N");
    expect_failure({"-", "-o", out()}, "'-': statmc cannot read images from standard input");
}

TEST_F(CliError, OiiotoolCommandsStatmcLacks)
{
    const auto in = input("in.exr", cli_render(0));
    for (const char* command : {"--flip", "-flop", "--over", "-otex", "--printstats"})
        expect_failure({in, command, "-o", out()},
                       std::string(command) +
                           " is an oiiotool command that statmc does not support");
    expect_failure({in, "--flipp", "-o", out()}, "unknown command '--flipp'");
    expect_failure({in, "--echo", "{TOP.width}"},
                   "'{TOP.width}': statmc does not evaluate oiiotool's {expressions}");
}

TEST_F(CliError, BadChannelLists)
{
    const auto in = input("in.exr", cli_render(0));
    expect_failure({in, "--ch", "R,Q", "-o", out()},
                   "--ch: no channel 'Q' (the image has R, G, B, A, albedo.R, albedo.G, albedo.B)");
    expect_failure({in, "--ch", "R,9", "-o", out()},
                   "--ch: channel index 9 is out of range (the image has 7 channels)");
    // A constant must be finite: "nan" is a channel name, and the image has none.
    expect_failure(
        {in, "--ch", "R,A=nan", "-o", out()},
        "--ch: no channel 'nan' (the image has R, G, B, A, albedo.R, albedo.G, albedo.B)");
    expect_failure({"-i:ch=R,variance.R", in, "-o", out()},
                   in + ": -i:ch: no channel 'variance.R'");
}

TEST_F(CliError, BadGeometryTypesAndCompression)
{
    const auto in = input("in.exr", cli_render(0));
    expect_failure({in, "--crop", "10y8", "-o", out()},
                   "--crop: geometry '10y8' is not WxH, WxH+X+Y or xmin,ymin,xmax,ymax");
    expect_failure({in, "--resize", "0x8", "-o", out()}, "--resize: geometry '0x8' has no pixels");
    // The whole line is checked before anything runs: the -o before a bad GEOM writes
    // nothing (expect_failure checks that no file was left).
    expect_failure({in, "-o", out(), "--crop", "10y8"},
                   "--crop: geometry '10y8' is not WxH, WxH+X+Y or xmin,ymin,xmax,ymax");
    expect_failure({in, "-o", out(), "--resize", "0x8"}, "--resize: geometry '0x8' has no pixels");
    expect_failure({in, "--compression", "dwaa", "-o", out()},
                   "--compression: 'dwaa' is lossy; statmc writes none, rle, zip, zips or piz");
    expect_failure({"-d", "uint8", in, "-o", out()},
                   "-d: OpenEXR stores half, float or uint32 channels, got 'uint8'");
    expect_failure({"-d", "R=half", in, "-o", out()}, "-d R=half: per-channel types");
    expect_failure({in, "-o:type=double", out()},
                   "-o:type: OpenEXR stores half, float or uint32 channels, got 'double'");
    expect_failure({in, "--mulc", "2,x", "-o", out()}, "--mulc: expected a finite number, got 'x'");
}

TEST_F(CliError, BadSubimagesAndOperands)
{
    const auto in = input("in.exr", cli_render(0));
    expect_failure({in, "--subimage", "beauty", "-o", out()},
                   "--subimage: " + in + " has no subimage 'beauty' (it has 1: (unnamed))");
    expect_failure({in, "--subimage:delete=1", "0", "-o", out()},
                   "has one subimage; deleting it would leave no image");
    expect_failure({"-a", in, in, "--siappend", in, "--add", "-o", out()},
                   "--add: " + in + " (--siappend) has 2 subimages but " + in + " has 1");
    expect_failure({in, "--mulc:subimages=2", "2", "-o", out()},
                   "--mulc: " + in + " has no subimage '2' (it has 1: (unnamed))");
    expect_failure({in, "--add", "-o", out()}, "--add: needs 2 images, the stack holds 1");
    expect_failure({"--colorconfig", dir.file("none.ocio"), in, "--colorconvert", "linear", "sRGB",
                    "-o", out()},
                   "--colorconfig: colour config " + dir.file("none.ocio"));
    if (!std::getenv("OCIO"))
        expect_failure({in, "--ociodisplay", "", "", "-o", out()},
                       "--ociodisplay: needs an OCIO config (--colorconfig FILE or $OCIO)");
}

// The state letter of process `pid` (from /proc/PID/stat), or 0 when it is gone; its
// parent's pid in `ppid`.
char process_state(const std::string& pid, long* ppid = nullptr)
{
    std::ifstream stat("/proc/" + pid + "/stat");
    std::string text;
    std::getline(stat, text);
    const std::size_t close = text.rfind(')');
    if (close == std::string::npos || close + 4 > text.size())
        return 0;
    if (ppid)
        *ppid = std::strtol(text.c_str() + close + 4, nullptr, 10);
    return text[close + 2];
}

// A child process of `parent`, once one has started (up to `wait`); -1 if none did.
long child_of(pid_t parent, std::chrono::seconds wait)
{
    const auto deadline = std::chrono::steady_clock::now() + wait;
    while (std::chrono::steady_clock::now() < deadline) {
        for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
            const std::string name = entry.path().filename().string();
            long ppid = 0;
            if (name.find_first_not_of("0123456789") == std::string::npos &&
                process_state(name, &ppid) != 0 && ppid == parent)
                return std::stol(name);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
}

TEST_F(CliError, AnInterruptWhileTheDecoderRunsEndsTheDecoderToo)
{
    const std::string in =
        input("in.exr", layers::make_statistics_image(noisy_statistics(32, 16, 8, 5), {"", 8, 5}));
    const std::string target = out();
    // Everything the child needs is made before fork: this process has threads.
    std::vector<std::string> env_text = {"STATMC_DECODE_FAULT=hang"};
    for (char** e = environ; *e; ++e)
        env_text.emplace_back(*e);
    std::vector<char*> env;
    for (std::string& e : env_text)
        env.push_back(e.data());
    env.push_back(nullptr);
    const int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    ASSERT_GE(devnull, 0);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(devnull, 1);
        ::dup2(devnull, 2);
        ::execle(STATMC_CLI_PATH, STATMC_CLI_PATH, in.c_str(), "-o", target.c_str(),
                 static_cast<char*>(nullptr), env.data());
        ::_exit(127);
    }
    ::close(devnull);
    const long decoder = child_of(pid, std::chrono::seconds(30));
    ::kill(pid, SIGINT);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_GT(decoder, 0) << "statmc started no decoder";
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
    // The decoder, which would hang for ever, ends with its parent (a zombie left to init
    // counts as ended).
    const std::string decoder_pid = std::to_string(decoder);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    char state = process_state(decoder_pid);
    while (state != 0 && state != 'Z' && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        state = process_state(decoder_pid);
    }
    EXPECT_TRUE(state == 0 || state == 'Z') << "decoder " << decoder << " is in state " << state;
    EXPECT_FALSE(std::filesystem::exists(target));
}

}  // namespace
}  // namespace statmc::test
