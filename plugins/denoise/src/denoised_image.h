// The denoise operator's writer: the filtered planes written into their channels of the
// result (a float copy of the input, or the input itself in place), the diagnostics
// channels added, and what the header records of the layers denoised.
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "mean_filter.h"
#include "method_stages.h"
#include "statmc/denoise/denoise_image_options.h"
#include "statmc/layers/statistics_layers.h"

namespace statmc::denoising {

// A dense plane over the input region, and the channel of the image it is written to.
struct ChannelWrite {
    int channel;
    const float* dense;
};

/// Writes each dense plane into its channel of `image` over the output region, row by row
/// in parallel. With `source`, each row is first copied from it (same spec): copying a
/// 1280×720 statistics image (~80 MB) and then patching it walked it twice, on one thread.
void write_channels(OIIO::ImageBuf& image, const OIIO::ImageBuf* source,
                    const std::vector<ChannelWrite>& writes, const Regions& regions, int nthreads);
/// The writes of `f`'s means into the mean channels of `ch`.
std::vector<ChannelWrite> mean_writes(const layers::StatisticsChannels& ch, const Filtered& f,
                                      const Regions& regions);
/// A float copy of `in`, every channel and attribute kept, with the filtered means.
OIIO::ImageBuf denoised_copy(const OIIO::ImageBuf& in, const layers::StatisticsChannels& ch,
                             const Filtered& f, const Regions& regions, int nthreads);
/// `result` with the diagnostics channels of `aov`, added (as zeros) unless an earlier
/// run left them; their indices in the returned image come back in `members`/`effective`.
OIIO::ImageBuf with_diagnostics_channels(const OIIO::ImageBuf& result, const std::string& aov,
                                         int& members, int& effective);
/// statmc:denoisedLayers of `spec` with the layers `opt` denoises added: what a later
/// denoise of the file is warned about.
std::string with_denoised_layers(const OIIO::ImageSpec& spec, const DenoiseImageOptions& opt);

}  // namespace statmc::denoising
