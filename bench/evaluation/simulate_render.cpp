// statmc-simulate: the statistics a Monte Carlo render of a known image would produce.
// Each pixel's samples are drawn from a gamma distribution (skewed, like path-traced
// radiance) whose mean is the reference pixel, and accumulated with core's accumulators.
// Denoising the result can then be scored against the reference itself.
#include <cstdio>
#include <random>
#include <string>

#include <CLI/CLI.hpp>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "statmc/core/statistics_image.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/statistics_layers.h"

namespace {

using namespace statmc;

OIIO::ImageBuf resized_reference(const std::string& path, int width, int height)
{
    OIIO::ImageBuf ref = layers::read_image_file(path);
    if (ref.nchannels() < 3)
        throw layers::FileError(path + ": needs R, G, B channels");
    if (width <= 0)
        return ref;
    OIIO::ImageSpec spec(width, height, ref.nchannels(), OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf small(spec);
    if (!OIIO::ImageBufAlgo::resize(small, ref))
        throw layers::FileError(path + ": cannot resize: " + small.geterror());
    return small;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "Simulates the per-pixel statistics of a Monte Carlo render of a reference image."};
    std::string input, output, resolution;
    int spp = 16;
    float shape = 0.5f;
    unsigned seed = 1;
    app.add_option("reference", input, "reference image (its pixels are the expected values)")
        ->required();
    app.add_option("-o,--output", output, "statistics EXR to write")->required();
    app.add_option("--spp", spp, "samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    app.add_option("--shape", shape, "gamma shape k (1 = exponential; smaller = more skewed)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--seed", seed, "random seed")->capture_default_str();
    app.add_option("--resolution", resolution, "WxH to resize the reference to first");
    CLI11_PARSE(app, argc, argv);

    try {
        int width = 0, height = 0;
        if (!resolution.empty() && std::sscanf(resolution.c_str(), "%dx%d", &width, &height) != 2)
            throw layers::FileError("--resolution: expected WxH, got '" + resolution + "'");
        const OIIO::ImageBuf ref = resized_reference(input, width, height);
        const OIIO::ROI roi = ref.roi();
        StatisticsImage<3> stats(roi.width(), roi.height());
        std::mt19937_64 rng(seed);
        float truth[3], sample[3];
        for (int y = 0; y < roi.height(); ++y)
            for (int x = 0; x < roi.width(); ++x) {
                ref.getpixel(roi.xbegin + x, roi.ybegin + y, truth, 3);
                for (int i = 0; i < spp; ++i) {
                    for (int c = 0; c < 3; ++c)
                        sample[c] =
                            truth[c] > 0
                                ? std::gamma_distribution<float>(shape, truth[c] / shape)(rng)
                                : 0.f;
                    stats.add(x, y, sample);
                }
            }
        layers::StatisticsMetadata meta;
        meta.spp = spp;
        meta.seed = int(seed);
        layers::write_image_file(layers::make_statistics_image(stats.planes(), meta), output);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "statmc-simulate: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
