// Variance denoising, after StatER (Sakai et al. 2025; docs/method.md §10): each pixel's
// variance estimate is replaced by a weighted mean of the estimates around it that it
// cannot be told apart from. A pixel whose few samples happened to agree (too small an
// s², a dark speckle that rejects every neighbour) or disagree (a firefly's s²) then takes
// its neighbourhood's steadier value.
#pragma once

#include <vector>

#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

struct VarianceFilterOptions {
    int radius = 3;  ///< disk radius in pixels, ≥ 1
    /// Significance of the test on ln σ², in (0, 1). Looser than the mean test's: at
    /// 0.005 a variance edge bleeds (docs/method.md §10 has the sweep).
    double alpha = 0.05;
    float sigma_spatial = 2.f;   ///< Gaussian spatial falloff in pixels, > 0
    float sigma_albedo = 0.02f;  ///< albedo guide falloff, > 0 (with an albedo guide)
    float sigma_normal = 0.1f;   ///< normal guide falloff, > 0 (with a normal guide)
    /// A pixel without an interval (n < 4 or s² = 0) keeps its own s² (false), or takes the
    /// weighted mean of its neighbours' that have one (true; its own when none has).
    bool borrow_without_interval = false;
    /// Prior degrees of freedom d₀ of an empirical-Bayes moderation (Smyth 2004): the result
    /// becomes (d₀·m + (n − 1)·s̃²)/(d₀ + n − 1), m the weighted mean of every neighbour's s²
    /// (no test), so that a pixel whose few samples happened to agree cannot claim a variance
    /// far below its neighbourhood's (docs/method.md §10). 0 = off.
    double prior_dof = 0;
    /// Significance of a test on the means that a neighbour must pass to enter the
    /// moderation's prior: |x̄_i − x̄_j| ≤ z·sqrt(s²_i/n_i + s²_j/n_j), z at 1 − α/2. A
    /// neighbour with another expectation (a caustic beside a dark corner) then lends its
    /// variance to nobody; one whose mean differs only by the noise its variance explains (a
    /// rare bright path) still does (docs/method.md §10). 0 = every usable neighbour.
    double prior_alpha = 0;
    /// true: the average above, over the neighbours whose intervals on ln σ² agree
    /// (StatER's variance denoising). false: each pixel keeps its own s², and only the
    /// moderation (prior_dof) pulls it towards its neighbourhood; the intervals are not
    /// computed. The default method measured the same either way and takes false, the
    /// cheaper (docs/method.md §10).
    bool interval_test = true;
};

/// The denoised per-sample variances of `view` in `domain` (BoxCox: the Box-Cox set, and
/// boxcoxM4 with the interval test; Untransformed: the variance, and M3 and M4 with the
/// interval test): dense, channel-major, width × height per channel. With the interval test,
/// neighbour j joins pixel i in channel c when their Bonett intervals (variance_interval.h)
/// agree:
///
///     |ln(c_i s²_i) − ln(c_j s²_j)| ≤ z · sqrt(se_i² + se_j²),   z at 1 − α/2
///
/// (without it, none joins a pixel that has an interval), and the result is Σ w_ij s²_j /
/// Σ w_ij over the members, w_ij the spatial Gaussian times the guides' Gaussians when
/// `guides` has them, as in the mean filter (docs/method.md §5; the centre has weight 1). A pixel
/// without an interval joins no other. Deterministic: the same result for any `nthreads` (0 = all
/// cores) and any `level` (the SIMD kernels add the same double products in the same order as the
/// scalar loop). Throws std::invalid_argument for bad options, a view without those planes, or a
/// level this CPU cannot run.
std::vector<float> denoise_variances(const StatisticsView& view, TestDomain domain,
                                     const Guides& guides = {},
                                     const VarianceFilterOptions& options = {}, int nthreads = 0,
                                     SimdLevel level = SimdLevel::Auto);

}  // namespace statmc
