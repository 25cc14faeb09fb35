#include "denoised_image.h"

#include <cstring>
#include <stdexcept>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagebufalgo_util.h>

#include "statmc/layers/float_pixels.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_names.h"

namespace statmc::denoising {

using layers::StatisticsChannels;

void write_channels(OIIO::ImageBuf& image, const OIIO::ImageBuf* source,
                    const std::vector<ChannelWrite>& writes, const Regions& regions, int nthreads)
{
    const OIIO::ImageSpec& spec = image.spec();
    const OIIO::ROI& out = regions.output;
    const OIIO::ROI& input = regions.input;
    const std::size_t row_bytes = std::size_t(spec.width) * image.pixel_stride();
    OIIO::ImageBufAlgo::parallel_image(
        image.roi(), OIIO::paropt(layers::thread_count(nthreads)), [&](OIIO::ROI rows) {
            for (int y = rows.ybegin; y < rows.yend; ++y) {
                float* to = static_cast<float*>(image.pixeladdr(spec.x, y));
                if (source)
                    std::memcpy(to, source->pixeladdr(spec.x, y), row_bytes);
                if (y < out.ybegin || y >= out.yend)
                    continue;
                const std::ptrdiff_t row =
                    std::ptrdiff_t(y - input.ybegin) * input.width() - input.xbegin;
                for (int x = out.xbegin; x < out.xend; ++x) {
                    if (!regions.writes(x, y))
                        continue;
                    float* pixel = to + std::size_t(x - spec.x) * spec.nchannels;
                    for (const ChannelWrite& w : writes)
                        pixel[w.channel] = w.dense[row + x];
                }
            }
        });
}

std::vector<ChannelWrite> mean_writes(const StatisticsChannels& ch, const Filtered& f,
                                      const Regions& regions)
{
    const std::size_t pixels = std::size_t(regions.input.width()) * regions.input.height();
    std::vector<ChannelWrite> writes;
    for (int c = 0; c < ch.channels(); ++c)
        writes.push_back({ch.mean[c], f.means.data() + c * pixels});
    return writes;
}

OIIO::ImageBuf denoised_copy(const OIIO::ImageBuf& in, const StatisticsChannels& ch,
                             const Filtered& f, const Regions& regions, int nthreads)
{
    OIIO::ImageBuf result(in.spec(), OIIO::InitializePixels::No);
    if (result.has_error() || !layers::has_local_float_pixels(result))
        throw std::runtime_error("cannot allocate the output image: " + result.geterror());
    write_channels(result, &in, mean_writes(ch, f, regions), regions, nthreads);
    return result;
}

OIIO::ImageBuf with_diagnostics_channels(const OIIO::ImageBuf& result, const std::string& aov,
                                         int& members, int& effective)
{
    const std::string names[2] = {
        layers::diagnostics_channel(aov, layers::kMembersChannel),
        layers::diagnostics_channel(aov, layers::kEffectiveSamplesChannel)};
    const OIIO::ImageSpec& spec = result.spec();
    std::vector<int> order;
    std::vector<float> values(spec.nchannels, 0.f);
    std::vector<std::string> new_names(spec.channelnames);
    for (int c = 0; c < spec.nchannels; ++c)
        order.push_back(c);
    for (const std::string& name : names)
        if (spec.channelindex(name) < 0) {
            order.push_back(-1);
            values.push_back(0.f);
            new_names.push_back(name);
        }
    OIIO::ImageBuf extended =
        OIIO::ImageBufAlgo::channels(result, int(order.size()), order, values, new_names);
    if (extended.has_error())
        throw std::runtime_error("cannot add the diagnostics channels: " + extended.geterror());
    members = extended.spec().channelindex(names[0]);
    effective = extended.spec().channelindex(names[1]);
    return extended;
}

std::string with_denoised_layers(const OIIO::ImageSpec& spec, const DenoiseImageOptions& opt)
{
    std::string layers = spec.get_string_attribute(layers::attr::kDenoisedLayers);
    std::vector<std::string> now = {opt.aov.empty() ? std::string("beauty") : opt.aov};
    now.insert(now.end(), opt.aovs.begin(), opt.aovs.end());
    for (const std::string& layer : now)
        if (("," + layers + ",").find("," + layer + ",") == std::string::npos)
            layers += (layers.empty() ? "" : ",") + layer;
    return layers;
}

}  // namespace statmc::denoising
