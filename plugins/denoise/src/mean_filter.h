// The calls into core's filter over the region a run reads: the lead's estimators (with
// the context channel), the filter or the radius ladder, and joint AOVs averaged with the
// lead's members or tested side by side.
#pragma once

#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/radius_ladder.h"
#include "statmc/core/statistics_view.h"

namespace statmc::denoising {

// What the filter gives over the input region, dense: the means channel-major, and the
// diagnostics planes when asked for.
struct Filtered {
    std::vector<float> means, members, effective_samples;
};

/// The lead's estimators, with the context channel when `context` > 0 (context_channel.h).
EstimatorImage lead_estimators(const StatisticsView& stats, TestDomain domain,
                               const DenoiseOptions& options, int context, int nthreads);
/// `est` (built from `stats` by lead_estimators) filtered; with `ladder`, each pixel at its
/// ICI radius (no diagnostics then).
Filtered filter_region(const StatisticsView& stats, const EstimatorImage& est, const Guides& guides,
                       const DenoiseOptions& options, bool diagnostics,
                       const RadiusLadderOptions* ladder, const PixelMask& wanted, int nthreads);
/// An AOV averaged with the members and weights of the lead's test: `lead`, the lead's
/// estimators, with the AOV's means put in as the values (docs/method.md §14).
Filtered filter_joint_aov(EstimatorImage& lead, const StatisticsView& aov, const Guides& guides,
                          const DenoiseOptions& options, const PixelMask& wanted, int nthreads);
/// The lead and every joint AOV filtered as one image whose test is all of theirs
/// (side_by_side): one membership and one set of weights for every channel, so sums hold.
/// Returns the lead's output and each AOV's, in order.
std::vector<Filtered> filter_joint_all(const StatisticsView& lead,
                                       const std::vector<StatisticsView>& aovs, TestDomain domain,
                                       const Guides& guides, const DenoiseOptions& options,
                                       const PixelMask& wanted, int nthreads);

}  // namespace statmc::denoising
