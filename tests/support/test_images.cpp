#include "test_images.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagecache.h>
#include <gtest/gtest.h>

#include "statmc/core/context_channel.h"
#include "statmc/core/plane.h"

namespace statmc::test {

namespace {

OIIO::ImageBuf with_channels(const OIIO::ImageBuf& buf, const std::vector<int>& order,
                             const std::vector<std::string>& names)
{
    OIIO::ImageBuf out;
    if (!OIIO::ImageBufAlgo::channels(out, buf, int(order.size()), order, {}, names))
        throw std::runtime_error("channels: " + out.geterror());
    return out;
}

}  // namespace

StatisticsPlanes noisy_statistics(int width, int height, int spp, std::uint32_t seed)
{
    StatisticsImage<3> image(width, height);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const float tint[3] = {1.f, 0.7f, 0.4f};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double base = (x < width / 2 ? 0.2 : 0.9) + 0.1 * y / height;
            const int n = spp + (x + y) % 3;
            for (int s = 0; s < n; ++s) {
                float sample[3];
                for (int c = 0; c < 3; ++c)
                    sample[c] = float(tint[c] * base * -std::log(1.0 - uniform(rng)));
                image.add(x, y, sample);
            }
        }
    return image.planes();
}

StatisticsPlanes variance_aov(StatisticsPlanes stats)
{
    for (auto* plane : {&stats.bc_mean, &stats.bc_variance, &stats.bc_moment3, &stats.moment3,
                        &stats.moment4, &stats.bc_moment4})
        plane->clear();
    return stats;
}

layers::GuidePlanes GuideData::planes() const
{
    const std::size_t n = albedo.size() / 3;
    layers::GuidePlanes g;
    for (int c = 0; c < 3; ++c) {
        g.albedo[c] = dense_plane(albedo.data() + c * n, width);
        g.normal[c] = dense_plane(normal.data() + c * n, width);
    }
    g.depth = dense_plane(depth.data(), width);
    return g;
}

GuideData make_guides(int width, int height, std::uint32_t seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.01f, 0.01f);
    GuideData g;
    g.width = width;
    const std::size_t n = std::size_t(width) * height;
    g.albedo.resize(3 * n);
    g.normal.resize(3 * n);
    g.depth.resize(n);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            const bool left = x < width / 2;
            const float a[3] = {left ? 0.3f : 0.8f, left ? 0.3f : 0.6f, left ? 0.3f : 0.4f};
            const float t = float(y) / height;
            const float nrm[3] = {0.f, std::sin(t), std::cos(t)};
            for (int c = 0; c < 3; ++c) {
                g.albedo[c * n + i] = a[c] + jitter(rng);
                g.normal[c * n + i] = nrm[c];
            }
            g.depth[i] = 1.f + float(y);
        }
    return g;
}

std::vector<float> core_filtered(const StatisticsView& stats, TestDomain domain,
                                 const Guides& guides, const DenoiseOptions& options, int context)
{
    EstimatorImage est = estimators_from_statistics(stats, domain);
    if (context > 0)
        est = with_context(est, context_source_channel(est.channels), context,
                           options.firefly_ratio, 1);
    const std::size_t n = std::size_t(stats.width) * stats.height;
    std::vector<float> out(n * est.channels);
    std::vector<Plane> planes;
    for (int c = 0; c < est.channels; ++c)
        planes.push_back(dense_plane(out.data() + c * n, stats.width));
    filter(est, guides, options, planes, {}, 1);
    out.resize(n * stats.channels);  // the context channel's average is not an output
    return out;
}

float channel_value(const OIIO::ImageBuf& buf, const std::string& name, int x, int y)
{
    const int c = buf.spec().channelindex(name);
    EXPECT_GE(c, 0) << "no channel " << name;
    return c < 0 ? NAN : buf.getchannel(x, y, 0, c);
}

OIIO::ImageBuf without_channels(const OIIO::ImageBuf& buf, const std::vector<std::string>& names)
{
    std::vector<int> order;
    std::vector<std::string> kept;
    for (int c = 0; c < buf.spec().nchannels; ++c) {
        const std::string& name = buf.spec().channelnames[c];
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            order.push_back(c);
            kept.push_back(name);
        }
    }
    return with_channels(buf, order, kept);
}

OIIO::ImageBuf with_retired_position_layers(const OIIO::ImageBuf& buf)
{
    std::vector<int> order;
    std::vector<float> values;
    std::vector<std::string> names;
    for (int c = 0; c < buf.spec().nchannels; ++c) {
        order.push_back(c);
        values.push_back(0.f);
        names.push_back(buf.spec().channelnames[c]);
    }
    for (const char* name :
         {"subpixel.U", "subpixel.V", "subpixel.UU", "subpixel.VV", "subpixel.UV", "covU.R",
          "covU.G", "covU.B", "covV.R", "covV.G", "covV.B", "boxcoxCovU.R", "boxcoxCovU.G",
          "boxcoxCovU.B", "boxcoxCovV.R", "boxcoxCovV.G", "boxcoxCovV.B"}) {
        order.push_back(-1);
        values.push_back(-0.25f);
        names.push_back(name);
    }
    OIIO::ImageBuf out;
    if (!OIIO::ImageBufAlgo::channels(out, buf, int(order.size()), order, values, names))
        throw std::runtime_error("channels: " + out.geterror());
    return out;
}

OIIO::ImageBuf renamed_channels(const OIIO::ImageBuf& buf, const std::string& from_layer,
                                const std::string& to_layer)
{
    std::vector<int> order;
    std::vector<std::string> names;
    for (int c = 0; c < buf.spec().nchannels; ++c) {
        std::string name = buf.spec().channelnames[c];
        if (name.rfind(from_layer + ".", 0) == 0)
            name = to_layer + name.substr(from_layer.size());
        order.push_back(c);
        names.push_back(name);
    }
    return with_channels(buf, order, names);
}

OIIO::ImageBuf reversed_channels(const OIIO::ImageBuf& buf)
{
    std::vector<int> order;
    std::vector<std::string> names;
    for (int c = buf.spec().nchannels - 1; c >= 0; --c) {
        order.push_back(c);
        names.push_back(buf.spec().channelnames[c]);
    }
    return with_channels(buf, order, names);
}

void set_channel(OIIO::ImageBuf& buf, const std::string& name, int x, int y, float value)
{
    const int c = buf.spec().channelindex(name);
    if (c < 0)
        throw std::runtime_error("no channel " + name);
    std::vector<float> pixel(buf.spec().nchannels);
    buf.getpixel(x, y, pixel.data(), int(pixel.size()));
    pixel[c] = value;
    buf.setpixel(x, y, pixel.data(), int(pixel.size()));
}

void write_exr(const OIIO::ImageBuf& buf, const std::string& path)
{
    if (!buf.write(path))
        throw std::runtime_error("write " + path + ": " + buf.geterror());
}

OIIO::ImageBuf read_exr(const std::string& path)
{
    OIIO::ImageBuf buf(path);
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error("read " + path + ": " + buf.geterror());
    // The shared cache would otherwise serve a later file of the same name stale.
    OIIO::ImageCache::create(true)->invalidate(OIIO::ustring(path), true);
    return buf;
}

}  // namespace statmc::test
