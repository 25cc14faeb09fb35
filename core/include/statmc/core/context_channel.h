// The context test (docs/method.md §5): a pixel that sees a sliver of a light, and whose
// few samples happened to miss it, looks statistically like the dark surface beside it, so
// the t-test lets it take that surface's value. Its surroundings do not look alike: the
// light is in its neighbourhood and not in the surface's. Testing the pixels' box means
// as well, a neighbour joins only where both the pixels and their surroundings agree, as
// NL-means compares patches, but with the t-test deciding.
#pragma once

#include "statmc/core/estimator_image.h"

namespace statmc {

/// `est` with one channel more, the context of channel `channel`: per pixel, the mean of
/// that channel's test means and values over the (2r + 1)² box around it (clamped at the
/// image's edges), the pixel itself left out, over the box's testable pixels that the
/// firefly guard at `firefly_ratio` lets the pixel accept (firefly_guard.h; 0 = all): a
/// firefly is then part of no context, its own included, with the test variance of a mean of
/// independent estimates, Σ T / k². The count stays the pixel's own, which only makes the
/// test's degrees of freedom fewer than the box's. A pixel whose box holds no testable
/// pixel keeps its own channel as context. The same result for any `nthreads` (0 = all
/// cores). Throws std::invalid_argument when `est` has kMaxEstimatorChannels channels
/// already, `channel` is not one of them, or radius < 1.
EstimatorImage with_context(const EstimatorImage& est, int channel, int radius, float firefly_ratio,
                            int nthreads = 0);

/// The channel whose surroundings the context test compares in an image of `channels`:
/// green (1), which carries most of the luminance, or the first.
inline int context_source_channel(int channels) { return channels >= 3 ? 1 : 0; }

}  // namespace statmc
