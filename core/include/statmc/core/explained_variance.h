// The explained-variance correction (after StatER, Sakai et al. 2025; docs/method.md §12):
// where a pixel's samples vary linearly with their position in the pixel (an edge, an
// emitter border, a gradient), that part of their spread is image structure, not noise.
#pragma once

#include <vector>

#include "statmc/core/statistics_view.h"

namespace statmc {

struct ExplainedVarianceOptions {
    /// A pixel's gradient is removed only where the regression of its samples on (u, v)
    /// is significant at this level (F test with 2 and n − 3 degrees of freedom); elsewhere
    /// the variance is left as it is, so that noise-only pixels keep their estimate.
    double alpha = 0.05;
};

/// Per pixel and channel, the residual variance of the samples about their least-squares
/// plane in (u, v), s²_r = (M2 − cᵀS⁻¹c)/(n − 3), in place of s² (c the value-position
/// co-moments, S the position ones). M3 and M4 are rescaled so that the skewness and
/// kurtosis stay as measured. Untransformed and Box-Cox planes are corrected where the view
/// has the variance with its co-moments (has_positions, has_box_cox_positions); pixels with n < 4
/// or a degenerate S keep theirs. Dense channel-major planes over the view; a plane the view
/// lacks stays empty.
struct ExplainedVariance {
    std::vector<float> variance, moment3, moment4;
    std::vector<float> bc_variance, bc_moment3, bc_moment4;
    std::size_t corrected_pixels = 0;  ///< pixel-channels whose gradient was removed

    /// `view` reading the corrected planes (this object must outlive the result).
    StatisticsView applied_to(StatisticsView view) const;
};

/// Throws std::invalid_argument when the view has no position co-moments.
ExplainedVariance remove_explained_variance(const StatisticsView& view,
                                            const ExplainedVarianceOptions& options = {},
                                            int nthreads = 0);

/// The residual sum of squares per sample, M2/n − cᵀS⁻¹c, of one pixel-channel from
/// per-sample moments (m2 = M2/n, cu = Σ(f − f̄)(u − ū)/n, ...); −1 when S is singular.
double residual_second_moment(double m2, double cu, double cv, double suu, double svv, double suv);

}  // namespace statmc
