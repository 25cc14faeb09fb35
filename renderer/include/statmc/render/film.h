// The film: what a render accumulates per pixel. The beauty goes into core's online
// statistics (exact, mergeable), the guides into plain sums averaged on output, the
// per-bounce quantities that ACRR and SMIS steer by into a compact buffer of what their
// estimates read, and, for a file that asks for per-bounce layers, every per-bounce
// quantity into full statistics.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "statmc/core/statistics_image.h"
#include "statmc/render/bounce_statistics.h"
#include "statmc/render/steering_statistics.h"

namespace statmc::render {

/// Per-pixel accumulators for the beauty, the guide sums and the per-bounce quantities.
struct Film {
    /// `steering`: the quantities ACRR and SMIS read; `layers`: those written as per-bounce
    /// layers (empty: none is tracked).
    Film(int width, int height, BounceLayout steering = {}, BounceLayout layers = {});
    int width, height;
    StatisticsImage<3> stats;
    std::vector<double> albedo_sum, normal_sum, depth_sum;  ///< channel-major sums
    /// Σ over samples of |albedo|² and |normal|²: the guides' noise (guide_variance).
    std::vector<double> albedo_squares, normal_squares;
    /// Σ of the samples' motion to the previous frame (X then Y), empty unless tracked.
    std::vector<double> motion_sum;
    std::unique_ptr<SteeringStatistics> steering;  ///< null when nothing steers
    std::unique_ptr<BounceStatistics> bounces;     ///< null when no file asks for them

    /// Guide averages as dense channel-major float planes (3, 3 and 1 channels).
    std::vector<float> albedo() const;
    std::vector<float> normal() const;
    std::vector<float> depth() const;
    /// Per-sample variance of the albedo and normal guides, summed over their channels
    /// (the albedoVariance/normalVariance layers; 0 below two samples).
    std::vector<float> albedo_variance() const;
    std::vector<float> normal_variance() const;
    /// Motion averages (X then Y), empty unless tracked.
    std::vector<float> motion() const;
    void track_motion() { motion_sum.assign(std::size_t(width) * height * 2, 0.0); }
    /// The per-pixel sample counts: smallest, largest, mean, and whether every pixel has the
    /// same.
    struct SampleCounts {
        int min = 0;
        int max = 0;
        double mean = 0;
        bool uniform = true;
    };
    SampleCounts sample_counts() const;

    /// What a film of this size holds while rendering, plus the float planes written out at
    /// the end: the figure the resolution limit checks before anything is allocated.
    static double bytes_needed(int width, int height, const BounceLayout& steering,
                               const BounceLayout& layers);
};

/// Throws std::runtime_error naming `source` (a Film directive's file:line, or
/// "--resolution") when width × height is not a resolution statmc-render can hold: each side
/// in 1..65536, and Film::bytes_needed within three quarters of this machine's physical memory.
void require_renderable_resolution(int width, int height, const BounceLayout& steering,
                                   const BounceLayout& layers, const std::string& source);

}  // namespace statmc::render
