// The isolated decoder (layers/isolated_decode.h): what it reads is, to the bit, what this
// process reads itself, for every kind of file statmc keeps (scanline and tiled, half,
// float and UINT channels, offset data windows, several parts, MIP levels); and a decoder
// that crashes or hangs becomes an error naming the file, leaving no process and no
// descriptor behind.
#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "read_error.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/isolated_decode.h"
#include "statmc/layers/statistics_layers.h"
#include "temp_dir.h"
#include "test_images.h"

namespace statmc::test {
namespace {

// An environment variable set for one scope.
struct ScopedEnv {
    std::string name;
    ScopedEnv(std::string n, const std::string& value) : name(std::move(n))
    {
        ::setenv(name.c_str(), value.c_str(), 1);
    }
    ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

std::size_t open_descriptors()
{
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator("/proc/self/fd"))
        ++n;
    return n;
}

// No child of this process is left, running or unreaped.
bool no_children()
{
    errno = 0;
    return ::waitpid(-1, nullptr, WNOHANG) == -1 && errno == ECHILD;
}

// A small statistics frame, after checking that the decoder that will read it was built.
std::string small_frame(const TempDir& dir)
{
    const std::string path = dir.file("frame.exr");
    layers::write_image_file(
        layers::make_statistics_image(noisy_statistics(20, 10, 8, 3), {"", 8, 1}), path);
    EXPECT_FALSE(layers::decoder_program().empty()) << "statmc-decode was not built";
    return path;
}

// Every subimage and MIP level read through the decoder and in this process: the same
// specs (every attribute) and the same bits.
void expect_isolated_read_is_the_same(const std::string& path)
{
    ASSERT_FALSE(layers::decoder_program().empty()) << "statmc-decode was not built";
    layers::ReadOptions in_process;
    in_process.check_structure = false;
    layers::MipLevels isolated_levels, own_levels;
    const auto isolated = layers::read_image_subimages(path, {}, &isolated_levels);
    const auto own = layers::read_image_subimages(path, in_process, &own_levels);
    ASSERT_EQ(isolated.size(), own.size());
    ASSERT_EQ(isolated_levels.size(), own_levels.size());
    auto same = [](const OIIO::ImageBuf& a, const OIIO::ImageBuf& b) {
        EXPECT_EQ(a.spec().serialize(OIIO::ImageSpec::SerialText),
                  b.spec().serialize(OIIO::ImageSpec::SerialText));
        ASSERT_EQ(a.spec().format, OIIO::TypeDesc::FLOAT);
        ASSERT_EQ(a.spec().image_bytes(), b.spec().image_bytes());
        EXPECT_EQ(std::memcmp(a.localpixels(), b.localpixels(), a.spec().image_bytes()), 0);
    };
    for (std::size_t s = 0; s < own.size(); ++s) {
        SCOPED_TRACE("subimage " + std::to_string(s));
        same(isolated[s], own[s]);
        ASSERT_EQ(isolated_levels[s].size(), own_levels[s].size());
        for (std::size_t m = 0; m < own_levels[s].size(); ++m)
            same(isolated_levels[s][m], own_levels[s][m]);
    }
}

TEST(IsolatedDecode, AStatisticsFrameReadsToTheBitAsInProcess)
{
    TempDir dir;
    const std::string path = dir.file("frame.exr");
    layers::write_image_file(
        layers::make_statistics_image(noisy_statistics(37, 23, 8, 3), {"", 8, 1}), path);
    expect_isolated_read_is_the_same(path);
}

TEST(IsolatedDecode, HalfAndUintChannelsAndAnOffsetWindowReadAsOiioReadsThem)
{
    TempDir dir;
    const std::string path = dir.file("mixed.exr");
    const int width = 9, height = 5;
    {  // Data window at (-3, 2) inside a 16 x 16 display window; R half, id UINT, Z float.
        Imf::Header header(Imath::Box2i({0, 0}, {15, 15}),
                           Imath::Box2i({-3, 2}, {-3 + width - 1, 2 + height - 1}));
        header.channels().insert("R", Imf::Channel(Imf::HALF));
        header.channels().insert("id", Imf::Channel(Imf::UINT));
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        std::vector<half> r(width * height);
        std::vector<unsigned> id(width * height);
        std::vector<float> z(width * height);
        for (int i = 0; i < width * height; ++i) {
            r[i] = half(0.1f * float(i));
            id[i] = 4000000000u - 7u * unsigned(i);
            z[i] = 1e5f / float(i + 1);
        }
        const std::ptrdiff_t origin = -(-3) - 2 * width;  // pixel (0, 0)'s index
        Imf::FrameBuffer buffer;
        buffer.insert("R", Imf::Slice(Imf::HALF, (char*)(r.data() + origin), 2, 2 * width));
        buffer.insert("id", Imf::Slice(Imf::UINT, (char*)(id.data() + origin), 4, 4 * width));
        buffer.insert("Z", Imf::Slice(Imf::FLOAT, (char*)(z.data() + origin), 4, 4 * width));
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(buffer);
        out.writePixels(height);
    }
    expect_isolated_read_is_the_same(path);
    // OIIO scales a UINT channel to [0, 1] in a float read; the decoder's bits are scaled
    // the same way (checked against the file's own value here, not only against OIIO).
    const OIIO::ImageBuf image = layers::read_image_file(path);
    const int id = image.spec().channelindex("id");
    ASSERT_GE(id, 0);
    EXPECT_FLOAT_EQ(image.getchannel(-3, 2, 0, id), float(4000000000.0 / 4294967295.0));
}

TEST(IsolatedDecode, TiledMipMapsAndSeveralPartsReadAsInProcess)
{
    TempDir dir;
    const std::string source = dir.file("source.exr");
    layers::write_image_file(
        layers::make_statistics_image(noisy_statistics(40, 27, 8, 3), {"", 8, 1}), source);
    const std::string texture = dir.file("texture.exr");
    OIIO::ImageSpec config;
    config.tile_width = config.tile_height = 16;
    ASSERT_TRUE(OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture,
                                                 OIIO::ImageBuf(source), texture, config))
        << OIIO::geterror();
    expect_isolated_read_is_the_same(texture);
    layers::MipLevels levels;
    layers::read_image_subimages(texture, {}, &levels);
    EXPECT_EQ(levels.at(0).size(), 5u);  // 20x13, 10x6, 5x3, 2x1, 1x1 below 40x27

    const std::string parts = dir.file("parts.exr");
    std::vector<OIIO::ImageBuf> two = {layers::read_image_file(source),
                                       layers::read_image_file(source)};
    two[0].specmod().attribute("oiio:subimagename", "first");
    two[1].specmod().attribute("oiio:subimagename", "second");
    layers::write_image_file(two, parts, layers::WriteOptions{});
    expect_isolated_read_is_the_same(parts);
    EXPECT_EQ(layers::read_image_subimages(parts).size(), 2u);
}

TEST(IsolatedDecode, ADecoderCrashIsAnErrorNamingTheFileAndLeavesNothingBehind)
{
    TempDir dir;
    const std::string path = small_frame(dir);
    const std::size_t descriptors = open_descriptors();
    const ScopedEnv fault("STATMC_DECODE_FAULT", "crash");
    // A sanitized decoder reports the crash and exits with a status of its own instead.
    const std::string e = read_error(path);
    EXPECT_TRUE(
        e.rfind(path + ": damaged OpenEXR file: the decoder died of ", 0) == 0 ||
        e.rfind(path + ": damaged OpenEXR file: the decoder stopped with exit status ", 0) == 0)
        << e;
    EXPECT_TRUE(no_children());
    EXPECT_EQ(open_descriptors(), descriptors);
}

TEST(IsolatedDecode, ADecoderHangIsStoppedAtItsTimeAndLeavesNothingBehind)
{
    TempDir dir;
    const std::string path = small_frame(dir);
    const std::size_t descriptors = open_descriptors();
    const ScopedEnv fault("STATMC_DECODE_FAULT", "hang");
    layers::ReadOptions options;
    options.decode_timeout = 1;
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(read_error(path, options),
              path + ": damaged OpenEXR file: the decoder did not finish in 1 s and was stopped");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
    EXPECT_TRUE(no_children());
    EXPECT_EQ(open_descriptors(), descriptors);
}

TEST(IsolatedDecode, ATruncatedFileIsDamagedThroughTheDecoderAndThroughTheCheckerWithoutIt)
{
    TempDir dir;
    const std::string good = dir.file("good.exr");
    layers::write_image_file(
        layers::make_statistics_image(noisy_statistics(40, 30, 8, 3), {"", 8, 1}), good);
    const std::string bytes = file_bytes(good);
    const std::string cut = dir.file("cut.exr");
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() * 3 / 4);
    EXPECT_EQ(read_error(cut).rfind(cut + ": damaged OpenEXR file: ", 0), 0u) << read_error(cut);
    // Without a decoder program (an empty $STATMC_DECODER), OpenEXR's checker guards.
    const ScopedEnv none("STATMC_DECODER", "");
    EXPECT_EQ(read_error(cut), cut + ": damaged OpenEXR file: OpenEXR's file check fails on it "
                                     "(truncated, or corrupted headers, offsets or pixel data)");
}

}  // namespace
}  // namespace statmc::test
