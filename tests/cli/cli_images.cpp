#include "cli_images.h"

#include <gtest/gtest.h>

#include "statmc/layers/statistics_layers.h"
#include "test_images.h"

namespace statmc::test {

OIIO::ImageBuf cli_statistics_image()
{
    const StatisticsPlanes stats = noisy_statistics(kCliWidth, kCliHeight, 8, 77);
    const GuideData guides = make_guides(kCliWidth, kCliHeight, 78);
    layers::StatisticsMetadata meta;
    meta.spp = 8;
    meta.seed = 77;
    return layers::make_statistics_image(stats, meta, guides.planes());
}

OIIO::ImageBuf cli_variance_aov_image()
{
    return layers::make_statistics_image(
        variance_aov(noisy_statistics(kCliWidth, kCliHeight, 8, 79)));
}

OIIO::ImageBuf cli_render(int k, int width, int height)
{
    OIIO::ImageSpec spec(width, height, 7, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B", "A", "albedo.R", "albedo.G", "albedo.B"};
    spec.alpha_channel = 3;
    OIIO::ImageBuf img(spec);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float noise = 0.1f * float((x * 5 + y * 3 + k * 7) % 5);
            const float level = x < width / 2 ? 0.2f : 0.9f;
            const float px[7] = {
                level + noise, 0.7f * level + noise, 0.4f * level + noise, 1.f, 0.5f, 0.5f, 0.5f};
            img.setpixel(x, y, px);
        }
    return img;
}

void expect_same_channels(const OIIO::ImageBuf& got, const OIIO::ImageBuf& want)
{
    ASSERT_EQ(got.spec().width, want.spec().width);
    ASSERT_EQ(got.spec().height, want.spec().height);
    for (int c = 0; c < want.spec().nchannels; ++c) {
        const std::string& name = want.spec().channelnames[c];
        const int gc = got.spec().channelindex(name);
        ASSERT_GE(gc, 0) << name;
        for (int y = want.spec().y; y < want.spec().y + want.spec().height; ++y)
            for (int x = want.spec().x; x < want.spec().x + want.spec().width; ++x)
                ASSERT_TRUE(same_bits(got.getchannel(x, y, 0, gc), want.getchannel(x, y, 0, c)))
                    << name << " at (" << x << ", " << y << ")";
    }
}

}  // namespace statmc::test
