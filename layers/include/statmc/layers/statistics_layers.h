// Reading and writing the per-pixel statistics of one AOV under the layer contract
// (docs/exr-layers.md): channels found by name, header attributes checked.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/statistics_image.h"
#include "statmc/core/statistics_view.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/layer_names.h"

namespace statmc::layers {

/// Where the statistics of one AOV live in an image: channel indices per statistic and
/// colour channel. An absent optional statistic has an empty index vector.
struct StatisticsChannels {
    std::string aov;                    ///< "" for the beauty
    std::vector<std::string> suffixes;  ///< R,G,B or Y
    int count = -1;                     ///< sampleCount.Y
    std::vector<int> mean, variance, bc_mean, bc_variance, bc_moment3;
    std::vector<int> moment3, moment4, bc_moment4;  ///< format version 2, optional
    bool variance_of_mean = false;                  ///< statmc:variance = "mean"

    int channels() const { return int(suffixes.size()); }
    bool has(Statistic stat) const { return !indices(stat).empty(); }
    bool has_box_cox() const;
    const std::vector<int>& indices(Statistic stat) const;
    std::vector<int>& indices(Statistic stat);
    /// The channel holding `stat` of colour channel c, e.g. "variance.G".
    std::string channel(Statistic stat, int c) const;
};

/// Finds the statistics of `aov` ("" = beauty) in `spec` by channel name. The mean and the
/// sample count are required; variance, the Box-Cox set and the higher moments are
/// optional, but a layer that is only partly present, an incomplete Box-Cox set or M3
/// without M4 (or the reverse) are errors.
/// Checks statmc:formatVersion (≤ kFormatVersion), statmc:boxcoxLambda (0.5 when
/// present) and statmc:variance ("sample" or "mean"). Throws LayerError naming the
/// layer or attribute.
StatisticsChannels find_statistics(const OIIO::ImageSpec& spec, std::string_view aov = "");

/// Throws LayerError naming the missing layer (with the layers `spec` does have) unless
/// `stat` is present.
void require_statistic(const OIIO::ImageSpec& spec, const StatisticsChannels& channels,
                       Statistic stat);

/// A core view of the statistics `channels` locates in `buf`; (0, 0) is the data
/// window's corner. The view points into `buf`, which must hold local float pixels
/// (see float_pixels.h) and outlive it.
StatisticsView statistics_view(const OIIO::ImageBuf& buf, const StatisticsChannels& channels);

/// find_statistics + statistics_view in one call.
StatisticsView read_statistics(const OIIO::ImageBuf& buf, std::string_view aov = "");

/// What a writer records beside the planes.
struct StatisticsMetadata {
    std::string aov;          ///< "" writes the beauty
    std::optional<int> spp;   ///< statmc:spp
    std::optional<int> seed;  ///< statmc:seed
};

/// A new float image (data window at the origin) holding `stats` under the contract's
/// names: the mean, sampleCount.Y and whichever of variance and the Box-Cox set the view
/// has, then the guides given, with the statmc: attributes and zip compression.
/// Throws LayerError for a channel count the contract cannot name (only 1 or 3).
OIIO::ImageBuf make_statistics_image(const StatisticsView& stats,
                                     const StatisticsMetadata& metadata = {},
                                     const GuidePlanes& guides = {});
OIIO::ImageBuf make_statistics_image(const StatisticsPlanes& stats,
                                     const StatisticsMetadata& metadata = {},
                                     const GuidePlanes& guides = {});

/// The statistics of one more AOV stored beside the beauty (e.g. a tracked bounce,
/// bounce_aov()). It shares the beauty's sampleCount.Y, so its count plane must equal it.
struct AovStatistics {
    std::string aov;
    StatisticsView stats;
};

/// make_statistics_image with `aovs` written after the beauty's statistics and before the
/// guides, each under its own prefix (mean, then variance and the Box-Cox set it has).
/// Throws LayerError for an invalid or repeated AOV name, another resolution, or a count
/// that differs from the beauty's.
OIIO::ImageBuf make_statistics_image(const StatisticsView& stats,
                                     const StatisticsMetadata& metadata, const GuidePlanes& guides,
                                     const std::vector<AovStatistics>& aovs);

}  // namespace statmc::layers
