// The firefly guard. The paper's symmetric test lets an estimator whose variance is huge —
// a firefly, or a pixel straddling a light's edge or a highlight — pass against nearly
// every neighbour, because its own uncertainty covers any difference. Such a member adds
// little but noise to a confident centre's average, and where it is also biased (the
// highlight next to a dark surface) its value spreads as a halo of radius r.
//
// For a centre whose average has many members, adding a member of variance v_f lowers the
// average's MSE only if v_f is within a small factor of the members' variance (the
// inverse-variance argument, docs/filter-design.md). The guard therefore lets centre i
// accept neighbour j only if j's noise level is at most `ratio` times i's reference level.
//
// The guard is mutual for a pixel whose value rests on several samples: a glint (a few
// bright hits among misses) that its dark neighbours refuse does not take them either, so
// it keeps its light instead of averaging it away. A pixel whose value rests on about one
// sample (support below kGlintSupport, estimator_image.h) is what the guard was made for,
// a firefly, and still takes its neighbourhood (docs/method.md, "The mutual guard").
#pragma once

#include <vector>

#include "statmc/core/estimator_image.h"

namespace statmc {

/// Per pixel (row-major): the noise level that a neighbour presents, and the largest
/// level that a centre accepts.
struct NoiseLevels {
    /// The per-sample variance on a scale nearly independent of brightness for shot-like
    /// noise, the largest over channels (context channels left out); 0 where the pixel is
    /// untestable. For full
    /// statistics it is the Box-Cox variance (test_variance × count). For the untransformed
    /// test it is the first-order stand-in for it, s²/μ: raw variances grow with
    /// brightness, and a bright pixel would look like a firefly next to a dark one.
    std::vector<float> level;
    /// ratio × max(own level, median of the testable 8-neighbours' levels). Where both are
    /// 0 the neighbourhood is noise-free: a lit pixel there (an emitter, a directly seen
    /// constant) is certain and takes only neighbours as certain (limit 0); a black one
    /// may be a run of zero samples in a sparsely lit region, and takes any level (+∞,
    /// the paper's filter) so that the rare samples still spread. +∞ too with fewer than
    /// three testable neighbours, and everywhere when ratio = 0.
    std::vector<float> limit;
    /// The level a centre presents to its neighbours' limits (the mutual half of the
    /// guard): `level` where its value rests on at least kGlintSupport samples, else 0 (it
    /// is refused by nobody's limit). All 0 where the estimators carry no support.
    std::vector<float> own;
    /// The largest own level a pixel lets take it as a member: its limit, but +∞ where the
    /// limit is 0 (a certain, noise-free pixel refuses noisy members to stay certain, not
    /// because they are outliers: a noisy pixel of its value may still take it).
    std::vector<float> mutual_limit;
};

/// The support (samples' worth, EstimatorImage::support) from which a pixel refused by its
/// neighbours keeps its own value: two bright hits agree on a glint, one is a firefly.
inline constexpr float kGlintSupport = 2.f;

/// Whether the guard can exclude anything: ratio > 0.
bool firefly_guard_applies(const EstimatorImage& est, float ratio);

/// Consistency: as n grows, the per-sample variances of pixels with equal expectations
/// converge to the same value, the ratio test stops excluding them and the filter is
/// the paper's.
NoiseLevels noise_levels(const EstimatorImage& est, float ratio);

}  // namespace statmc
