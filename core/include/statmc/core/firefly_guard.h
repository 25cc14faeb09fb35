// Fireflies: pixels holding a sample that their neighbourhood's noise essentially never
// produces. The paper's symmetric test lets such a pixel, whose variance is huge, join
// nearly every neighbour's average, so its energy spreads as a faint disk of radius r and
// confident neighbours (few members) take a large share of it. The guard keeps a firefly
// out of its neighbours' averages while it still averages them itself.
#pragma once

#include <cstdint>
#include <vector>

#include "statmc/core/estimator_image.h"

namespace statmc {

/// Per pixel (row-major), 1 where the pixel is a firefly: in some channel its per-sample
/// variance in the test domain (test_variance × count: the Box-Cox variance for full
/// statistics, which is nearly independent of brightness for shot-like noise) exceeds
/// `ratio` times the median of its testable 8-neighbours', and that median is positive.
/// A zero median means the neighbourhood has no measurable noise: a lone non-zero pixel
/// there is a sparse but legitimate sample, and the paper's averaging is kept for it.
/// Untestable pixels and pixels with fewer than three testable neighbours are never
/// fireflies. ratio = 0 flags nothing.
///
/// Consistency: as n grows, a legitimate rare path is sampled by the neighbours too and
/// the variances converge, so the guard stops flagging and the filter becomes the paper's.
std::vector<std::uint8_t> find_fireflies(const EstimatorImage& est, float ratio);

}  // namespace statmc
