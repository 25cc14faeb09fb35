// How many degrees of freedom a pixel's own s² is worth where the samples are not normal
// (docs/method.md §10). Under a normal model s² ~ σ²χ²_d/d, and ln s² scatters around ln σ²
// with variance ψ'(d/2) (ψ' the trigamma function). Heavy tails (rare bright paths) make
// s² far noisier than that: a pixel that has not yet met the paths has an s² far below σ²,
// one that has met them one far above. The scatter of ln s² over a pixel's neighbourhood
// shows it, and the d whose ψ'(d/2) matches that scatter is what the pixel's s² is worth
// against the moderation's prior, as limma estimates a prior's weight from the same
// scatter (Smyth 2004).
#pragma once

#include <vector>

#include "statmc/core/filter.h"
#include "variance_filter_layout.h"

namespace statmc::detail {

/// Per channel and pixel of `L` (channel-major, as its planes): the variance of ln s² over
/// the (2·radius + 1)² square around the pixel, weighted by a separable Gaussian of `sigma`
/// pixels, among the pixels whose `L.prior_s2` is finite and positive; 0 where it is not
/// positive (fewer than two such pixels, or all alike). True differences of σ² across the
/// square (an edge) only make it larger. Deterministic for any thread count. With `wanted`
/// (PixelMask), only rows holding a wanted pixel are filled (0 elsewhere).
std::vector<float> log_variance_scatter(const VarianceLayout& L, int radius, double sigma,
                                        const PixelMask& wanted = {});

/// The degrees of freedom d whose ψ'(d/2) is `scatter`: +∞ where it is 0.
double scatter_dof(float scatter);

/// The x > 0 with ψ'(x) = y for y > 0, within 1e-4 relative for ψ'(1e7) ≤ y ≤ ψ'(1e-4)
/// (interpolated in a table of ln ψ' built once); clamped to that range outside it.
double inverse_trigamma(double y);

}  // namespace statmc::detail
