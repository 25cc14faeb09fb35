// statmc's oiiotool commands against the real oiiotool: each command line runs through
// both on the same generated EXRs, and the outputs must be the same file as far as a
// reader can tell (pixels bit for bit, channel names and types, subimages, compression,
// data and display windows) or print the same report.
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "statmc/layers/exr_files.h"

#include "cli_images.h"
#include "cli_runner.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

namespace fs = std::filesystem;

// Debian's openimageio-tools puts it here; $OIIOTOOL overrides.
std::string oiiotool_path()
{
    if (const char* env = std::getenv("OIIOTOOL"))
        return env;
    return "/usr/bin/oiiotool";
}

enum class Compare { Image, Text };

struct Case {
    std::string name;
    std::vector<std::string> args;  ///< "@x" is file x in the test directory; "OUT" the output
    Compare what = Compare::Image;
    std::string shows{};  ///< text oiiotool's report must hold: the case tests what it says
};

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.name; }

// A multi-part file: the render's RGBA as part "rgba", the statistics' variance as
// part "variance" (channels R,G,B), both 24x16.
void write_parts(const std::string& path)
{
    const OIIO::ImageBuf render = cli_render(0);
    const OIIO::ImageBuf stats = cli_statistics_image();
    std::vector<OIIO::ImageBuf> parts;
    parts.push_back(OIIO::ImageBufAlgo::channels(render, 4, {0, 1, 2, 3}));
    const int v[3] = {stats.spec().channelindex("variance.R"),
                      stats.spec().channelindex("variance.G"),
                      stats.spec().channelindex("variance.B")};
    const std::string rgb[3] = {"R", "G", "B"};
    parts.push_back(OIIO::ImageBufAlgo::channels(stats, 3, v, {}, rgb));
    parts[0].specmod().attribute("oiio:subimagename", "rgba");
    parts[1].specmod().attribute("oiio:subimagename", "variance");
    std::vector<OIIO::ImageSpec> specs = {parts[0].spec(), parts[1].spec()};
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out && out->open(path, 2, specs.data())) << OIIO::geterror();
    ASSERT_TRUE(parts[0].write(out.get())) << parts[0].geterror();
    ASSERT_TRUE(out->open(path, specs[1], OIIO::ImageOutput::AppendSubimage)) << out->geterror();
    ASSERT_TRUE(parts[1].write(out.get())) << parts[1].geterror();
    ASSERT_TRUE(out->close());
}

// Empty for an unreadable file, which the callers' assertions then name.
std::vector<OIIO::ImageBuf> read_subimages(const std::string& path)
{
    try {
        return layers::read_image_subimages(path);
    } catch (const std::exception&) {
        return {};
    }
}

// The headers as stored (the pixel types); empty for an unreadable file.
std::vector<OIIO::ImageSpec> read_headers(const std::string& path)
{
    try {
        return layers::read_image_headers(path);
    } catch (const std::exception&) {
        return {};
    }
}

void expect_same_file(const std::string& got_path, const std::string& want_path)
{
    const std::vector<OIIO::ImageBuf> got = read_subimages(got_path);
    const std::vector<OIIO::ImageBuf> want = read_subimages(want_path);
    const std::vector<OIIO::ImageSpec> got_headers = read_headers(got_path);
    const std::vector<OIIO::ImageSpec> want_headers = read_headers(want_path);
    ASSERT_FALSE(want.empty()) << "oiiotool wrote no readable " << want_path;
    ASSERT_EQ(got.size(), want.size()) << "subimages";
    ASSERT_EQ(got_headers.size(), got.size());
    ASSERT_EQ(want_headers.size(), want.size());
    for (std::size_t s = 0; s < want.size(); ++s) {
        SCOPED_TRACE("subimage " + std::to_string(s));
        const OIIO::ImageSpec &g = got_headers[s], &w = want_headers[s];
        EXPECT_EQ(g.channelnames, w.channelnames);
        for (int c = 0; c < std::min(g.nchannels, w.nchannels); ++c)
            EXPECT_EQ(g.channelformat(c), w.channelformat(c)) << w.channelnames[c];
        EXPECT_EQ(g.get_string_attribute("compression"), w.get_string_attribute("compression"));
        EXPECT_EQ(g.get_string_attribute("oiio:subimagename"),
                  w.get_string_attribute("oiio:subimagename"));
        EXPECT_EQ(OIIO::get_roi(g), OIIO::get_roi(w)) << "data window";
        EXPECT_EQ(OIIO::get_roi_full(g), OIIO::get_roi_full(w)) << "display window";
        if (g.nchannels != w.nchannels || OIIO::get_roi(g) != OIIO::get_roi(w))
            continue;
        const auto cr = OIIO::ImageBufAlgo::compare(got[s], want[s], 0.0f, 0.0f);
        EXPECT_FALSE(cr.error);
        EXPECT_EQ(cr.nfail, 0u) << "max error " << cr.maxerror << " at (" << cr.maxx << ", "
                                << cr.maxy << ") channel " << w.channelnames[cr.maxc];
        EXPECT_EQ(cr.maxerror, 0.0);
    }
}

// oiiotool's -a --stats heads subimage 1 with the file's subimage count, a quirk statmc
// does not copy; the rest of every report must match line for line.
std::string without_subimage_headings(const std::string& text)
{
    std::istringstream lines(text);
    std::string line, kept;
    while (std::getline(lines, line))
        if (line.rfind(" subimage ", 0) != 0)
            kept += line + "\n";
    return kept;
}

class OiiotoolCompat : public ::testing::TestWithParam<Case> {
protected:
    static void SetUpTestSuite()
    {
        if (!fs::exists(oiiotool_path()))
            return;
        dir = new TempDir;
        write_exr(cli_statistics_image(), dir->file("stats.exr"));
        write_exr(cli_render(0), dir->file("render.exr"));
        write_exr(cli_render(1), dir->file("render2.exr"));
        write_parts(dir->file("parts.exr"));
        // Per-channel types: half colour, float alpha and albedo.
        OIIO::ImageBuf mixed = cli_render(0);
        const OIIO::TypeDesc half = OIIO::TypeDesc::HALF, full = OIIO::TypeDesc::FLOAT;
        const OIIO::TypeDesc types[7] = {half, half, half, full, full, full, full};
        mixed.set_write_format(types);
        write_exr(mixed, dir->file("mixed.exr"));
        // Data window inside a larger display window.
        write_exr(OIIO::ImageBufAlgo::crop(cli_render(0), OIIO::ROI(2, 6, 3, 7, 0, 1, 0, 7)),
                  dir->file("cropped.exr"));
    }
    static void TearDownTestSuite()
    {
        delete dir;
        dir = nullptr;
    }

    std::vector<std::string> command_line(const std::vector<std::string>& args,
                                          const std::string& out) const
    {
        std::vector<std::string> line;
        for (const std::string& a : args)
            line.push_back(a == "OUT" ? out : a.rfind("@", 0) == 0 ? dir->file(a.substr(1)) : a);
        return line;
    }

    static TempDir* dir;
};

TempDir* OiiotoolCompat::dir = nullptr;

TEST_P(OiiotoolCompat, SameResultAsOiiotool)
{
    if (!fs::exists(oiiotool_path()))
        GTEST_SKIP() << "oiiotool not found at " << oiiotool_path()
                     << " (install openimageio-tools or set $OIIOTOOL)";
    const Case& c = GetParam();
    const std::string want_out = dir->file(c.name + "-oiiotool.exr");
    const std::string got_out = dir->file(c.name + "-statmc.exr");
    const CliResult want = run_program(oiiotool_path(), command_line(c.args, want_out));
    const CliResult got = run_cli(command_line(c.args, got_out));
    EXPECT_EQ(got.exit_code, want.exit_code) << "statmc: " << got.err << "\noiiotool: " << want.err;
    if (c.what == Compare::Text) {
        EXPECT_NE(want.out, "");
        EXPECT_NE(want.out.find(c.shows), std::string::npos) << want.out;
        EXPECT_EQ(without_subimage_headings(got.out), without_subimage_headings(want.out));
        return;
    }
    ASSERT_EQ(want.exit_code, 0) << want.err;
    ASSERT_EQ(got.exit_code, 0) << got.err;
    expect_same_file(got_out, want_out);
}

const Case kCases[] = {
    // Channels.
    {"ch_select", {"@stats.exr", "--ch", "R,G,B", "-o", "OUT"}},
    {"ch_shuffle_rename_constant",
     {"@stats.exr", "--ch", "B,G,R,A=1,var.R=variance.R,3", "-o", "OUT"}},
    {"input_ch", {"-i:ch=R,G,B,variance.R,variance.G,variance.B", "@stats.exr", "-o", "OUT"}},
    {"input_ch_now_float", {"-i:ch=B,sampleCount.Y:type=float:now=1", "@stats.exr", "-o", "OUT"}},
    {"chnames", {"@render.exr", "--chnames", "X,,Z", "-o", "OUT"}},
    {"chappend",
     {"@render.exr", "@stats.exr", "--ch", "variance.R,variance.G,variance.B", "--chappend", "-o",
      "OUT"}},
    {"chappend_n_duplicate_names",
     {"@render.exr", "--ch", "R,G,B", "@render.exr", "--ch", "A", "@render2.exr", "--ch", "A",
      "--chappend:n=3", "-o", "OUT"}},
    // Arithmetic.
    {"add", {"@render.exr", "@render2.exr", "--add", "-o", "OUT"}},
    {"sub", {"@render.exr", "@render2.exr", "--sub", "-o", "OUT"}},
    {"mul", {"@render.exr", "@render2.exr", "--mul", "-o", "OUT"}},
    {"mulc", {"@render.exr", "--mulc", "2.5", "-o", "OUT"}},
    {"mulc_per_channel", {"@render.exr", "--mulc", "0.5,2,4", "-o", "OUT"}},
    {"addc_per_channel", {"@render.exr", "--addc", "0.25,-0.5", "-o", "OUT"}},
    // Colour.
    {"colorconvert", {"@render.exr", "--colorconvert", "linear", "sRGB", "-o", "OUT"}},
    {"colorconvert_alpha",
     {"@render.exr", "--ch", "R,G,B,A=0.5", "--colorconvert", "linear", "Rec709", "-o", "OUT"}},
    {"colorconvert_unpremult",
     {"@render.exr", "--ch", "R,G,B,A=0.5", "--colorconvert:unpremult=1", "sRGB", "linear", "-o",
      "OUT"}},
    {"ociodisplay_alpha",
     {"--colorconfig", STATMC_DISPLAY_CONFIG, "@render.exr", "--ch", "R,G,B,A=0.5", "--ociodisplay",
      "sRGB", "Filmic", "-o", "OUT"}},
    {"ociodisplay",
     {"--colorconfig", STATMC_DISPLAY_CONFIG, "@render.exr", "--ociodisplay", "sRGB", "Filmic",
      "-o", "OUT"}},
    // Geometry.
    {"crop", {"@render.exr", "--crop", "10x8+4+2", "-o", "OUT"}},
    {"crop_pad", {"@render.exr", "--crop", "2,3,30,20", "-o", "OUT"}},
    {"resize", {"@render.exr", "--resize", "12x8", "-o", "OUT"}},
    {"resize_percent_filter", {"@render.exr", "--resize:filter=box", "200%", "-o", "OUT"}},
    {"resize_origin", {"@render.exr", "--resize", "30x20+2-1", "-o", "OUT"}},
    // GEOM is the display window; the data window inside it scales along.
    {"resize_windowed", {"@cropped.exr", "--resize", "12x8", "-o", "OUT"}},
    {"resize_windowed_percent", {"@cropped.exr", "--resize", "75%", "-o", "OUT"}},
    {"crop_windowed", {"@cropped.exr", "--crop", "3x5", "-o", "OUT"}},
    // Subimages.
    {"subimage_by_name", {"@parts.exr", "--subimage", "variance", "-o", "OUT"}},
    {"subimage_delete", {"@parts.exr", "--subimage:delete=1", "0", "-o", "OUT"}},
    {"siappend", {"@parts.exr", "--subimage", "rgba", "@render2.exr", "--siappend", "-o", "OUT"}},
    {"siappend_n", {"@parts.exr", "@render.exr", "@render2.exr", "--siappend:n=3", "-o", "OUT"}},
    {"copy_all_parts", {"@parts.exr", "-o", "OUT"}},
    {"first_part_without_a", {"@parts.exr", "--mulc", "2", "-o", "OUT"}},
    {"all_parts", {"-a", "@parts.exr", "--mulc", "2", "-o", "OUT"}},
    {"named_parts", {"@parts.exr", "--mulc:subimages=variance", "3", "-o", "OUT"}},
    {"all_parts_ch", {"-a", "@parts.exr", "--ch", "R,G", "-o", "OUT"}},
    // Output format.
    {"d_half", {"-d", "half", "@render.exr", "-o", "OUT"}},
    {"o_type_half", {"@render.exr", "-o:type=half", "OUT"}},
    {"compression_piz", {"@render.exr", "--compression", "piz", "-o", "OUT"}},
    {"compression_zips_half",
     {"@stats.exr", "--ch", "R,G,B", "-d", "half", "--compression", "zips", "-o", "OUT"}},
    // Reports.
    {"info", {"--info", "@render.exr", "@parts.exr"}, Compare::Text},
    {"info_verbose", {"--info", "-v", "@stats.exr"}, Compare::Text},
    {"info_verbose_modifier",
     {"--info:verbose=1", "@render.exr"},
     Compare::Text,
     "channel list: R, G, B, A, albedo.R, albedo.G, albedo.B"},
    {"info_verbose_parts",
     {"-a", "--info", "-v", "@parts.exr"},
     Compare::Text,
     "2 subimages: 24x16 [f,f,f,f], 24x16 [f,f,f]"},
    {"info_windows",
     {"--info", "-v", "@cropped.exr"},
     Compare::Text,
     "pixel data origin: x=2, y=3"},
    {"stats", {"--stats", "@render.exr"}, Compare::Text},
    {"info_stats_mixed_types",
     {"--info", "-v", "--stats", "@mixed.exr"},
     Compare::Text,
     "half/half/half/float/float/float/float"},
    {"mixed_types_to_float", {"@mixed.exr", "-d", "float", "-o", "OUT"}},
    {"stats_parts", {"-a", "--stats", "@parts.exr"}, Compare::Text},
    {"diff_fails", {"@render.exr", "@render2.exr", "--diff"}, Compare::Text, "FAILURE"},
    {"diff_passes", {"@render.exr", "@render.exr", "--diff"}, Compare::Text, "PASS"},
    {"echo",
     {"--echo", "hello statmc", "--echo:newline=0", "no newline", "--echo", "!"},
     Compare::Text},
};

INSTANTIATE_TEST_SUITE_P(Commands, OiiotoolCompat, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return info.param.name; });

// The one deliberate difference (docs/oiiotool.md): without -d, oiiotool
// keeps a half input half, statmc writes float32 as the layer contract requires.
TEST(OiiotoolDifference, HalfInputIsWrittenAsFloatUnlessAsked)
{
    if (!fs::exists(oiiotool_path()))
        GTEST_SKIP() << "oiiotool not found at " << oiiotool_path();
    TempDir dir;
    write_exr(cli_render(0), dir.file("render.exr"));
    auto oiiotool = [&](const std::vector<std::string>& args) {
        return run_program(oiiotool_path(), args).exit_code;
    };
    ASSERT_EQ(oiiotool({"-d", "half", dir.file("render.exr"), "-o", dir.file("half.exr")}), 0);
    ASSERT_EQ(oiiotool({dir.file("half.exr"), "--mulc", "2", "-o", dir.file("oiiotool.exr")}), 0);
    ASSERT_EQ(
        run_cli({dir.file("half.exr"), "--mulc", "2", "-o", dir.file("statmc.exr")}).exit_code, 0);
    EXPECT_EQ(read_headers(dir.file("oiiotool.exr")).at(0).format, OIIO::TypeDesc::HALF);
    EXPECT_EQ(read_headers(dir.file("statmc.exr")).at(0).format, OIIO::TypeDesc::FLOAT);
    // The values are the same: doubling a half is exact.
    const auto cr =
        OIIO::ImageBufAlgo::compare(read_subimages(dir.file("statmc.exr"))[0],
                                    read_subimages(dir.file("oiiotool.exr"))[0], 0.0f, 0.0f);
    EXPECT_EQ(cr.maxerror, 0.0);
}

}  // namespace
}  // namespace statmc::test
