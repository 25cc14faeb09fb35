// What runs on one image: the test's domain, the statistics it reads, and the stages of
// the chosen method (the radius ladder, the context test) that the image can feed, with
// the halo they read beyond the output region.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/estimator_image.h"
#include "statmc/core/radius_ladder.h"
#include "statmc/denoise/denoise_image_options.h"
#include "statmc/layers/statistics_layers.h"

namespace statmc::denoising {

// What is written (the ROI within the data window) and what the filter reads: the ROI
// grown by the radius, so that ROI pixels come out exactly as in a full-frame run.
// `wanted`, over `input` (empty: all of `output`): the pixels of `output` that a masked
// denoise computes and writes (PixelMask).
struct Regions {
    OIIO::ROI output;
    OIIO::ROI input;
    PixelMask wanted;

    bool writes(int x, int y) const
    {
        return wanted.empty() ||
               wanted[std::size_t(y - input.ybegin) * input.width() + (x - input.xbegin)];
    }
};

/// `where`: the denoise's mask over `src`'s data window (empty: every pixel).
Regions regions_for(const OIIO::ImageBuf& src, const OIIO::ROI& roi, int radius,
                    const PixelMask& where);

/// The domain `choice` resolves to for `ch`; a missing layer it needs is a LayerError.
TestDomain choose_domain(const OIIO::ImageSpec& spec, const layers::StatisticsChannels& ch,
                         TestDomainChoice choice);
/// `ch` narrowed to what the test in `domain` reads, and the untransformed variance when
/// `variance` (the radius ladder's).
layers::StatisticsChannels used_channels(layers::StatisticsChannels ch, TestDomain domain,
                                         bool variance);
/// Validates the statistics `ch` selects over `region` (layers::validate_statistics), as
/// `opt.nonfinite` says; a problem is a LayerError naming the channel and pixel.
void check_statistics(const OIIO::ImageBuf& in, const layers::StatisticsChannels& ch,
                      const DenoiseImageOptions& opt, const OIIO::ROI& region);

// The method's stages around the mean filter (the radius ladder, the context test) that
// run on this image, and the halo they read.
struct Stages {
    bool radius_ladder = false;
    int context_radius = 0;  ///< 0: no context test
    RadiusLadderOptions ladder;
    std::string skipped;  ///< the stages left out, and why ("" when none)

    // The ladder's variance filter and the context boxes read beyond the mean filter's
    // halo, and the ladder's checks read the output that far around a pixel.
    int halo() const
    {
        return std::max(radius_ladder ? ladder.variance.radius : 0, context_radius) +
               (radius_ladder ? checks_reach(ladder) : 0);
    }
};

/// The stages of `opt`'s method that run on an image whose lead statistics are `all`;
/// `side_by_side`: joint AOVs tested together (joint_aovs.h), which leaves no room for the
/// context channel.
Stages stages_for(const layers::StatisticsChannels& all, bool side_by_side,
                  const DenoiseImageOptions& opt);

}  // namespace statmc::denoising
