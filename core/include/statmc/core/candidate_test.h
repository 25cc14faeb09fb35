// Holding another estimate of a pixel's expectation (a neural denoiser's output) to the
// pixel's own samples (docs/method.md §15). Under the hypothesis that candidate c_i is the
// pixel's expectation μ_i, the difference x̄_i − c_i has mean 0 and variance ṽ_i/n_i, ṽ
// the moderated per-sample variance (variance_filter.h). A candidate is rejected where
// that difference is too large for the samples to explain, in the pixel alone or in the
// mean over a small box around it: a denoiser's errors (a dimmed highlight, an invented
// edge) span several pixels, which the box sees with more power than one pixel at few
// samples.
#pragma once

#include <cstdint>
#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

struct CandidateTestOptions {
    /// The chance that a correct candidate is rejected at a pixel, in (0, 1): it is split
    /// evenly between the pixel's test and the box's, and within each between the
    /// channels (Bonferroni), so the rate is at most alpha whatever the correlations.
    double alpha = 0.001;
    /// The box's radius b: the mean difference over the (2b + 1)² pixels around (clamped at
    /// the image's edges) is tested too. 0: the pixel alone, with all of alpha.
    int box_radius = 1;
    /// The degrees of freedom the moderation's prior adds to a pixel's own n − 1 (the
    /// prior_dof of the variances given; 0 when they are the pixels' own s²).
    double prior_dof = 16;
};

/// Why a pixel's candidate was rejected (bits; 0: kept).
enum CandidateRejection : std::uint8_t {
    kRejectedByPixel = 1,  ///< the pixel's own difference
    kRejectedByBox = 2,    ///< the box's mean difference
};

/// Per pixel of `stats` (row-major), the CandidateRejection bits of `candidate` (one plane
/// per channel of `stats`). `variance`: per-sample variances, dense and channel-major
/// (denoise_variances' layout). A pixel with n < 2, a non-finite mean or variance is
/// untestable: it rejects nothing and adds nothing to its neighbours' boxes. A variance
/// of 0 rejects any difference. The test per pixel and channel:
///
///     |d̄| > t(α', df) · sqrt(V)
///
/// the pixel: d̄ = x̄ − c, V = ṽ/n, df = n − 1 + prior_dof; the box: d̄ and V the mean
/// difference and its variance over the box's testable pixels, df by Welch–Satterthwaite.
/// Deterministic for any `nthreads` (0 = all cores). Throws std::invalid_argument for bad
/// options, or planes that do not match `stats`.
std::vector<std::uint8_t> test_candidate(const StatisticsView& stats,
                                         const std::vector<float>& variance,
                                         const std::vector<ConstPlane>& candidate,
                                         const CandidateTestOptions& options = {},
                                         int nthreads = 0);

}  // namespace statmc
