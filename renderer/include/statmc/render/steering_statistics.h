// What steering reads of the per-bounce quantities (ACRR §7, SMIS §8), and nothing more:
// per pixel and tracked quantity, its mean, and the Box-Cox mean, variance and third
// moment the estimates' test reads (docs/method.md §3), in one compact pixel-major buffer.
// The updates are core's (CentralMoments), stopped at the third moment, so the estimates
// are to the bit those of the full per-bounce statistics (bounce_statistics.h), which a
// render keeps only for files that ask for per-bounce layers (--bounce-layers).
#pragma once

#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/render/bounce_layout.h"
#include "statmc/render/bounce_statistics.h"

namespace statmc::render {

class SteeringStatistics {
public:
    /// One quantity's accumulator at one pixel (the count is the pixel's).
    struct Moments {
        double mean = 0;                           ///< of the values (what the estimates average)
        double bc_mean = 0, bc_m2 = 0, bc_m3 = 0;  ///< of their Box-Cox transforms (the test)
    };

    SteeringStatistics(int width, int height, BounceLayout layout);

    const BounceLayout& layout() const { return layout_; }
    /// Adds one sample: `values` holds layout().quantities() floats (bounce_sample). A value
    /// that is not finite, or clearly negative, counts as 0, as core's accumulators count it.
    void add(int x, int y, const float* values);

    /// Denoises every quantity, four to a filter call (as bounce_statistics.h says why),
    /// Box-Cox test, without guides.
    BounceEstimates denoise(const DenoiseOptions& options, int threads = 0) const;

    /// The accumulators, as checkpoints save and restore them: the counts per pixel, and
    /// the moments pixel-major (pixel i's quantities contiguous).
    std::vector<double>& counts() { return count_; }
    std::vector<Moments>& moments() { return moments_; }

private:
    int width_, height_;
    BounceLayout layout_;
    std::vector<double> count_;
    std::vector<Moments> moments_;
};

}  // namespace statmc::render
