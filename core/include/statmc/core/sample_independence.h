// Whether two sets of samples could be independent: the statistics assume every sample is
// drawn once, so two renders made with one seed (Blender's default seed 0 without the
// animated seed, a farm that gave every frame the same --seed) must not be averaged or
// merged as if they were twice the samples (docs/method.md, "Independent samples").
#pragma once

#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

/// Whether channel planes `a` and `b` (one plane per channel, equal counts) hold the same
/// bits at every pixel of a width × height image: two renders that drew the same samples.
bool identical_pixels(const std::vector<ConstPlane>& a, const std::vector<ConstPlane>& b,
                      int width, int height);

/// Pixels of two frames' statistics compared where the first carries noise.
struct SharedNoise {
    long noisy = 0;      ///< pixels of `a` with a variance above 0 in some channel
    long identical = 0;  ///< of those, pixels whose means and variances equal `b`'s bit for bit

    /// Independent samples of a noisy pixel all but never repeat a mean and a variance to
    /// the bit; a pixel of a static region rendered twice with one seed always does. More
    /// than half the noisy pixels repeated is the second case (docs/method.md).
    bool same_samples() const { return noisy > 0 && 2 * identical > noisy; }
};

/// Compares `a` and `b` (same size and channels) pixel for pixel: the untransformed mean and
/// variance where `a` has them, else the Box-Cox ones.
SharedNoise shared_noise(const StatisticsView& a, const StatisticsView& b);

}  // namespace statmc
