// Writes the broken and edge-case EXRs of the file corpus test into a directory, with a
// manifest of what each of `statmc FILE -o OUT`, `statmc FILE --denoise -o OUT` and
// `statmc --info -v FILE` must end in: "ok" (exit 0 and a readable output), "error" (exit 1
// and one "statmc: error:" line naming the file), or "either"; and the file, if any, whose
// pixels a successful copy must equal. The files are made at test time, so nothing large
// is committed. Usage: statmc_make_test_files DIR
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/statistics_layers.h"
#include "test_images.h"

namespace {

std::string directory;
std::ofstream manifest;

// `reference`: a file whose pixels a successful copy must equal ("-": none).
void expect(const std::string& file, const char* copy, const char* denoise, const char* info,
            const std::string& reference = "-")
{
    manifest << file << ' ' << copy << ' ' << denoise << ' ' << info << ' ' << reference << '\n';
}

std::string path_of(const std::string& file) { return directory + "/" + file; }

std::string read_bytes(const std::string& file)
{
    std::ifstream in(path_of(file), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const std::string& file, const std::string& bytes)
{
    std::ofstream(path_of(file), std::ios::binary | std::ios::trunc) << bytes;
}

void write(const OIIO::ImageBuf& image, const std::string& file)
{
    if (!image.write(path_of(file)))
        throw std::runtime_error(file + ": " + image.geterror());
}

// A statistics image as statmc-render writes one: 24x16, 8 spp, Box-Cox set and all.
OIIO::ImageBuf statistics(int width = 24, int height = 16)
{
    return statmc::layers::make_statistics_image(
        statmc::test::noisy_statistics(width, height, 8, 7), {"", 8, 7});
}

// The header attribute `name` of type `type`: where its value starts in `bytes`.
std::size_t attribute_value(const std::string& bytes, const std::string& name,
                            const std::string& type)
{
    const std::string key = name + '\0' + type + '\0';
    const std::size_t at = bytes.find(key);
    if (at == std::string::npos)
        throw std::runtime_error("no attribute " + name);
    return at + key.size() + 4;  // past the value's size
}

void put_int(std::string& bytes, std::size_t at, int value)
{
    std::memcpy(&bytes[at], &value, 4);  // OpenEXR is little-endian, as is this machine
}

void valid_files()
{
    write(statistics(), "statistics.exr");
    expect("statistics.exr", "ok", "ok", "ok", "statistics.exr");

    write(statistics(1, 1), "one_pixel.exr");
    expect("one_pixel.exr", "ok", "ok", "ok");

    OIIO::ImageBuf shifted = statistics();
    shifted.set_origin(-8, -4);
    write(shifted, "negative_origin.exr");
    expect("negative_origin.exr", "ok", "ok", "ok");

    // The statistics plus 1,000 more channels: a renderer with many AOVs.
    OIIO::ImageBuf stats = statistics();
    OIIO::ImageSpec extra(stats.spec().width, stats.spec().height, 1000, OIIO::TypeDesc::HALF);
    for (int c = 0; c < 1000; ++c)
        extra.channelnames[c] = "aov" + std::to_string(c) + ".Y";
    OIIO::ImageBuf aovs(extra);
    OIIO::ImageBufAlgo::fill(aovs, {0.25f});
    write(OIIO::ImageBufAlgo::channel_append(stats, aovs), "thousand_channels.exr");
    expect("thousand_channels.exr", "ok", "ok", "ok", "thousand_channels.exr");

    // Statistics in part 0 and a beauty in part 1, both tiled.
    OIIO::ImageBuf beauty(OIIO::ImageSpec(24, 16, 3, OIIO::TypeDesc::HALF));
    OIIO::ImageBufAlgo::fill(beauty, {0.5f, 0.25f, 0.125f});
    OIIO::ImageSpec specs[2] = {stats.spec(), beauty.spec()};
    for (OIIO::ImageSpec& spec : specs) {
        spec.tile_width = spec.tile_height = 16;
        spec.attribute("compression", "piz");
    }
    auto out = OIIO::ImageOutput::create("exr");
    const std::string multipart = path_of("tiled_multipart.exr");
    if (!out->open(multipart, 2, specs) || !stats.write(out.get()) ||
        !out->open(multipart, specs[1], OIIO::ImageOutput::AppendSubimage) ||
        !beauty.write(out.get()) || !out->close())
        throw std::runtime_error("tiled_multipart.exr: " + out->geterror());
    expect("tiled_multipart.exr", "ok", "ok", "ok", "tiled_multipart.exr");

    // MIP levels: a copy keeps them; there are no statistics to denoise.
    OIIO::ImageSpec mip_spec(32, 32, 3, OIIO::TypeDesc::HALF);
    mip_spec.tile_width = mip_spec.tile_height = 16;
    OIIO::ImageBuf level0(mip_spec);
    OIIO::ImageBufAlgo::checker(level0, 4, 4, 1, {0.1f, 0.1f, 0.1f}, {0.9f, 0.8f, 0.7f});
    auto mip_out = OIIO::ImageOutput::create("exr");
    const std::string mipmapped = path_of("mipmapped.exr");
    mip_spec.attribute("textureformat", "Plain Texture");  // OIIO writes levels only then
    if (!mip_out->open(mipmapped, mip_spec) || !level0.write(mip_out.get()))
        throw std::runtime_error("mipmapped.exr: " + mip_out->geterror());
    for (int size = 16; size >= 1; size /= 2) {
        OIIO::ImageSpec level_spec = mip_spec;
        level_spec.width = level_spec.height = level_spec.full_width = level_spec.full_height = size;
        OIIO::ImageBuf level = OIIO::ImageBufAlgo::resample(level0, false, OIIO::ROI(0, size, 0, size));
        if (!mip_out->open(mipmapped, level_spec, OIIO::ImageOutput::AppendMIPLevel) ||
            !level.write(mip_out.get()))
            throw std::runtime_error("mipmapped.exr: " + mip_out->geterror());
    }
    mip_out->close();
    expect("mipmapped.exr", "ok", "error", "ok", "mipmapped.exr");

    {  // A rip map: levels that shrink in x and y separately, which a copy cannot keep.
        Imf::Header header(32, 16);
        header.channels().insert("Y", Imf::Channel(Imf::HALF));
        header.setTileDescription(Imf::TileDescription(16, 16, Imf::RIPMAP_LEVELS));
        Imf::TiledOutputFile rip(path_of("ripmap.exr").c_str(), header);
        std::vector<half> pixels(32 * 16, half(0.5f));
        for (int ly = 0; ly < rip.numYLevels(); ++ly)
            for (int lx = 0; lx < rip.numXLevels(); ++lx) {
                Imf::FrameBuffer frame;
                frame.insert("Y", Imf::Slice(Imf::HALF, reinterpret_cast<char*>(pixels.data()),
                                             sizeof(half), sizeof(half) * rip.levelWidth(lx)));
                rip.setFrameBuffer(frame);
                rip.writeTiles(0, rip.numXTiles(lx) - 1, 0, rip.numYTiles(ly) - 1, lx, ly);
            }
    }
    expect("ripmap.exr", "error", "error", "error");

    // A plain half RGB beauty: copies, but has no statistics to denoise.
    write(beauty, "rgb_half.exr");
    expect("rgb_half.exr", "ok", "error", "ok", "rgb_half.exr");
}

void suspicious_files()
{
    // NaN in the statistics: a faithful copy is fine; the denoiser names the channel.
    OIIO::ImageBuf nan = statistics();
    const int variance = nan.spec().channelindex("variance.G");
    const std::vector<float> nans(std::size_t(nan.nchannels()),
                                  std::numeric_limits<float>::quiet_NaN());
    OIIO::ImageBufAlgo::fill(nan, nans, OIIO::ROI(3, 4, 2, 3, 0, 1, variance, variance + 1));
    write(nan, "nan_statistics.exr");
    expect("nan_statistics.exr", "ok", "error", "ok");

    // Statistics stored with lossy compression (PXR24 drops 8 bits of every float).
    OIIO::ImageBuf lossy = statistics();
    lossy.specmod().attribute("compression", "pxr24");
    write(lossy, "lossy_statistics.exr");
    expect("lossy_statistics.exr", "ok", "either", "ok");

    // Two channels renamed to one name in the header: OpenEXR keeps one of them, so a read
    // would silently lose the other.
    OIIO::ImageBuf rs(OIIO::ImageSpec(8, 8, 2, OIIO::TypeDesc::FLOAT));
    rs.specmod().channelnames = {"R", "S"};
    write(rs, "duplicate_channels.exr");
    std::string bytes = read_bytes("duplicate_channels.exr");
    const std::size_t s = bytes.find(std::string("S\0", 2), bytes.find("channels"));
    bytes[s] = 'R';
    write_bytes("duplicate_channels.exr", bytes);
    expect("duplicate_channels.exr", "error", "error", "error");
}

void broken_files()
{
    const std::string good = read_bytes("statistics.exr");
    for (double fraction : {0.0, 0.001, 0.01, 0.1, 0.5, 0.9, 0.999}) {
        const std::string file = "truncated_" + std::to_string(int(fraction * 1000)) + ".exr";
        write_bytes(file, good.substr(0, std::size_t(fraction * double(good.size()))));
        expect(file, "error", "error", "error");
    }

    {  // A string attribute that declares nearly 2 GB in a 38 KB file (OpenEXR would
       // allocate it before reading).
        std::string bytes = good;
        put_int(bytes, attribute_value(bytes, "statmc:variance", "string") - 4, 0x70000000);
        write_bytes("attribute_larger_than_file.exr", bytes);
        expect("attribute_larger_than_file.exr", "error", "error", "error");
    }

    {  // Tiles of 16 x 20 000 000 pixels on a 32 x 32 image (a reader allocates a whole tile).
        std::string bytes = read_bytes("mipmapped.exr");
        put_int(bytes, attribute_value(bytes, "tiles", "tiledesc") + 4, 20000000);
        write_bytes("huge_tiles.exr", bytes);
        expect("huge_tiles.exr", "error", "error", "error");
    }

    write_bytes("not_an_exr.exr", std::string(4096, '\x5a'));
    expect("not_an_exr.exr", "error", "error", "error");

    // Data windows of zero and negative width (xMax = xMin - 1, xMin - 10).
    for (int shrink : {1, 10}) {
        std::string bytes = good;
        const std::size_t window = attribute_value(bytes, "dataWindow", "box2i");
        int x_min = 0;
        std::memcpy(&x_min, &bytes[window], 4);
        put_int(bytes, window + 8, x_min - shrink);
        const std::string file = shrink == 1 ? "zero_width_window.exr" : "negative_window.exr";
        write_bytes(file, bytes);
        expect(file, "error", "error", "error");
    }

    {  // A 100000 x 100000 header with its full offset table and no pixels.
        Imf::Header header(100000, 100000);
        for (const char* c : {"R", "G", "B"})
            header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        Imf::OutputFile out(path_of("huge_window.exr").c_str(), header);
    }
    expect("huge_window.exr", "error", "error", "error");

    // Multi-part files whose part 0 declares fewer or more chunks than its tiles need.
    // OpenEXR may read past the count it can recompute; then the copy must be the image.
    const std::string parts = read_bytes("tiled_multipart.exr");
    for (int change : {-1, 7}) {
        std::string bytes = parts;
        const std::size_t chunks = attribute_value(bytes, "chunkCount", "int");
        int count = 0;
        std::memcpy(&count, &bytes[chunks], 4);
        put_int(bytes, chunks, count + change);
        const std::string file = change < 0 ? "chunk_count_short.exr" : "chunk_count_long.exr";
        write_bytes(file, bytes);
        expect(file, "either", "either", "either", "tiled_multipart.exr");
    }

    OIIO::ImageSpec deep_spec(4, 3, 1, OIIO::TypeDesc::FLOAT);
    deep_spec.deep = true;
    write(OIIO::ImageBuf(deep_spec), "deep.exr");
    expect("deep.exr", "error", "error", "error");
}

}  // namespace

int main(int argc, char* argv[])
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: statmc_make_test_files DIR\n");
        return 2;
    }
    directory = argv[1];
    manifest.open(directory + "/manifest.txt");
    try {
        valid_files();
        suspicious_files();
        broken_files();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "statmc_make_test_files: %s\n", e.what());
        return 1;
    }
    return manifest.good() ? 0 : 1;
}
