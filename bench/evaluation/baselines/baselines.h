// Classic denoisers that statmc is evaluated against (docs/evaluation.md). They work on
// core planes like the StatMC filter, so the comparison times the filters alone.
#pragma once

#include <array>

#include "statmc/core/filter.h"
#include "statmc/core/plane.h"

namespace statmc::baselines {

/// Non-local means with per-pixel variance (Rousselle, Knaus & Zwicker 2012, Eq. 3–5):
/// the patch distance of pixel p to q is the mean over patch pixels and channels of
///     ((u_p − u_q)² − α(v_p + min(v_p, v_q))) / (ε + k²(v_p + v_q)),
/// with v the variance of the mean, and q weighs exp(−max(0, distance)).
struct NlmOptions {
    int search_radius = 10;  ///< (2r+1)² neighbours
    int patch_radius = 3;    ///< (2f+1)² patch
    float k = 0.45f;         ///< their damping factor
    float alpha = 1.f;       ///< variance cancellation
};

/// `mean` and `variance` (of the mean): three planes each, w × h; `out` three planes.
void nlm(const std::array<ConstPlane, 3>& mean, const std::array<ConstPlane, 3>& variance, int w,
         int h, const NlmOptions& options, const std::array<Plane, 3>& out);

/// A cross (joint) bilateral filter on the feature buffers alone: weights
/// exp(−|Δp|²/2σ_s²) · exp(−|Δalbedo|²/2σ_a²) · exp(−|Δnormal|²/2σ_n²), no colour term —
/// the classic feature-guided filter (Eisemann & Durand 2004, Petschnigg et al. 2004).
struct CrossBilateralOptions {
    int radius = 10;
    float sigma_spatial = 4.f;
    float sigma_albedo = 0.1f;
    float sigma_normal = 0.2f;
};

void cross_bilateral(const std::array<ConstPlane, 3>& mean, const Guides& guides, int w, int h,
                     const CrossBilateralOptions& options, const std::array<Plane, 3>& out);

}  // namespace statmc::baselines
