// Moderated variances (docs/method.md §10), after StatER's idea of filtering variances
// (Sakai et al. 2025): each pixel's per-sample variance is pulled towards the weighted mean
// of its neighbours' whose means agree with its own, as empirical Bayes moderates
// gene-expression variances (Smyth 2004). A pixel whose few samples happened to agree (too
// small an s², a dark speckle) then cannot claim a precision its neighbourhood does not
// have. The radius ladder's intervals and verify's test read it.
#pragma once

#include <vector>

#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

struct VarianceFilterOptions {
    int radius = 3;  ///< disk radius in pixels, ≥ 1
    /// A pixel's own s² counts as an estimate where n ≥ 4, n > z and s² > 0, z the normal
    /// quantile at 1 − α/2; in (0, 1).
    double alpha = 0.05;
    float sigma_spatial = 2.f;   ///< Gaussian spatial falloff in pixels, > 0
    float sigma_albedo = 0.02f;  ///< albedo guide falloff, > 0 (with an albedo guide)
    float sigma_normal = 0.1f;   ///< normal guide falloff, > 0 (with a normal guide)
    /// A pixel without an estimate (n < 4 or s² = 0) keeps its own s² (false), or takes the
    /// weighted mean of its neighbours' that have one (true; its own when none has).
    bool borrow_without_interval = false;
    /// Prior degrees of freedom d₀ of the moderation: the result becomes
    /// (d₀·m + (n − 1)·s²)/(d₀ + n − 1), m the weighted mean of the usable neighbours' s²
    /// (those that pass the test of prior_alpha). 0 = off.
    double prior_dof = 0;
    /// Significance of a test on the means that a neighbour must pass to enter the
    /// moderation's prior: |x̄_i − x̄_j| ≤ z·sqrt(s²_i/n_i + s²_j/n_j), z at 1 − α/2. A
    /// neighbour with another expectation (a caustic beside a dark corner) then lends its
    /// variance to nobody; one whose mean differs only by the noise its variance explains (a
    /// rare bright path) still does (docs/method.md §10). 0 = every usable neighbour.
    double prior_alpha = 0;
    /// With the moderation: a pixel whose s² is below its prior counts it with
    /// min(n − 1, d) degrees of freedom rather than n − 1, d the one whose ψ'(d/2) is the
    /// variance of ln s² over the (2·radius + 1)² square around it (Gaussian sigma_spatial).
    /// Heavy tails (rare bright paths, met by some pixels and not yet by others) make s²
    /// far noisier than n − 1 allows, and mostly too small: such a pixel then leans on its
    /// neighbourhood's variance (docs/method.md §10).
    bool own_dof_from_scatter = false;
};

/// The moderated per-sample variances of `view` in `domain` (BoxCox: the Box-Cox set;
/// Untransformed: the variance): dense, channel-major, width × height per channel. The
/// weights are the spatial Gaussian times the guides' Gaussians when `guides` has them, as
/// in the mean filter (docs/method.md §5; the centre has weight 1). Deterministic: the same
/// result for any `nthreads` (0 = all cores) and any `level` (the SIMD kernels add the same
/// double products in the same order as the scalar loop). `wanted`: only those pixels
/// (PixelMask). Throws std::invalid_argument for bad options, a view without those planes,
/// or a level this CPU cannot run.
std::vector<float> denoise_variances(const StatisticsView& view, TestDomain domain,
                                     const Guides& guides = {},
                                     const VarianceFilterOptions& options = {}, int nthreads = 0,
                                     SimdLevel level = SimdLevel::Auto,
                                     const PixelMask& wanted = {});

}  // namespace statmc
