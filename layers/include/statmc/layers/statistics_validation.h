// Checks that stored statistics are statistics: counts ≥ 1, variances ≥ 0, values finite.
// Each problem names the channel and its first offending pixel, so that a broken frame
// can be traced to a renderer bug rather than silently denoised.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/statistics_layers.h"

namespace statmc::layers {

/// One kind of problem in one channel: the first offending pixel (image coordinates, row
/// by row) and how many pixels have it.
struct StatisticsProblem {
    std::string channel;  ///< e.g. "variance.G"
    std::string what;     ///< e.g. "negative value -0.3", "n = 0", "NaN"
    int x = 0, y = 0;
    std::size_t pixels = 0;

    /// "variance.G: negative value -0.3 at pixel (12, 7) [3 pixels affected]"
    std::string message() const;
};

struct ValidationOptions {
    /// NaN and ±Inf are problems; when false they are left to core, which counts them
    /// as 0 and keeps such pixels out of every test.
    bool nonfinite_is_problem = true;
    /// Pixels to check, in image coordinates; the default is the data window.
    OIIO::ROI roi = {};
};

/// Checks every statistic `channels` locates in `buf` (local float pixels):
/// sampleCount.Y ≥ 1; variances and fourth moments ≥ 0; Box-Cox means ≥ −2 (the
/// transform's minimum); each fourth moment M4/n at least (M2/n)² of its domain; and,
/// unless disabled, no NaN or Inf anywhere. Empty when all is well.
std::vector<StatisticsProblem> validate_statistics(const OIIO::ImageBuf& buf,
                                                   const StatisticsChannels& channels,
                                                   const ValidationOptions& options = {});

/// The messages of `problems`, joined by "; ".
std::string join_messages(const std::vector<StatisticsProblem>& problems);

}  // namespace statmc::layers
