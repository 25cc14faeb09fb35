// Per-pixel statistics (docs/method.md §2, core's accumulators) of the per-bounce quantities of
// a BounceLayout, in full, for a file's per-bounce layers (--bounce-layers); steering keeps
// only what it reads (steering_statistics.h). The quantities are packed as channels, four to
// a StatisticsImage<4> group.
//
// Denoising them for steering is batched the same way: four quantities to a filter call
// (core's filter takes 1..4 channels), so each iteration costs ceil(Q/4) filter calls, i.e.
// one pass over the image per group, instead of Q. The filter's membership test then
// requires all channels of a group to pass (docs/method.md §3), so the groups are filtered
// a little more conservatively than one quantity alone would be: the price of batching,
// which can only make an estimate noisier, never the render biased (the estimates only
// steer sampling).
#pragma once

#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/filter.h"
#include "statmc/core/statistics_image.h"

#include "statmc/render/bounce_layout.h"
#include "statmc/render/integrator.h"

namespace statmc::render {

/// One camera sample's value of every quantity of `layout` (`out` holds
/// layout.quantities() floats), from the sample's path record:
/// - L_j = luminance of Σ (contributions added at vertices ≥ j) / β_j, channel by
///   channel (β_j the throughput on arrival at vertex j), times the roulette weight
///   Π 1/p before j; 0 when the path ended before j. L_0 is the sample's luminance.
///   The roulette weight makes L_j a Horvitz-Thompson estimate of the radiance from
///   vertex j as if no roulette had cut paths short before it: without it, every path
///   that roulette ended early would count as darkness, the more so the more ACRR
///   terminates, and L̂_j would drift towards 0 (escapes and absorption stay zeros,
///   rightly: they are what continuing a path would give).
/// - wins at vertex b < M: a light sample with power-heuristic weight > 0.5 is a light
///   win, else a BSDF win; a BSDF-sampled emitter hit with weight > 0.5 a BSDF win, else
///   a light win (§8).
void bounce_sample(const PathRecord& record, const BounceLayout& layout, float* out);

/// The denoised estimates of every pixel, pixel-major (pixel i's quantities contiguous).
struct BounceEstimates {
    BounceLayout layout;
    std::vector<float> values;

    PixelEstimates pixel(std::size_t i) const
    {
        return {values.data() + i * std::size_t(layout.quantities()), &layout};
    }
};

class BounceStatistics {
public:
    static constexpr int kGroup = 4;  ///< channels per group: the filter's maximum

    BounceStatistics(int width, int height, BounceLayout layout);

    const BounceLayout& layout() const { return layout_; }
    /// Adds one sample: `values` holds layout().quantities() floats (bounce_sample).
    void add(int x, int y, const float* values);

    /// The statistics planes of every group (channel c of group g is quantity 4g + c).
    std::vector<StatisticsPlanes> group_planes() const;
    /// The one-channel view of quantity q inside `groups` (as group_planes() returned).
    static StatisticsView quantity_view(const std::vector<StatisticsPlanes>& groups, int q);

    /// The accumulators, four quantities to a group: what a checkpoint saves and restores.
    std::vector<StatisticsImage<kGroup>>& groups() { return groups_; }
    const std::vector<StatisticsImage<kGroup>>& groups() const { return groups_; }

private:
    BounceLayout layout_;
    std::vector<StatisticsImage<kGroup>> groups_;
};

}  // namespace statmc::render
