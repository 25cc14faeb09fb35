// Read-only views of per-pixel statistics planes, in the form the EXR layer contract stores.
#pragma once

#include <array>

#include "statmc/core/plane.h"

namespace statmc {

/// Per-pixel statistics of a C-channel quantity. Variances are per sample, s² = M2/(n − 1),
/// unless `variance_of_mean` says the untransformed `variance` planes are already divided
/// by n (renderers' "mse" AOVs); the Box-Cox variance is always per sample. bc_moment3 is the third
/// central moment M3/n of the Box-Cox samples. Box-Cox planes may be absent (renderers
/// that write only a variance AOV). The higher moments (format version 2) are optional
/// too: moment3/moment4 = M3/n, M4/n of the untransformed samples, bc_moment4 = M4/n of
/// the Box-Cox ones (docs/method.md §10). So are the position co-moments (§12): per pixel
/// the mean sub-pixel offset (subpixel_u, subpixel_v) and its central sums per sample
/// (subpixel_uu = Σ(u − ū)²/n, subpixel_vv, subpixel_uv); per channel Σ(f − f̄)(u − ū)/n and
/// Σ(f − f̄)(v − v̄)/n of the untransformed (cov_u, cov_v) and Box-Cox (bc_cov_u, bc_cov_v)
/// samples.
struct StatisticsView {
    int width = 0;
    int height = 0;
    int channels = 0;
    ConstPlane count;
    std::array<ConstPlane, 4> mean{};
    std::array<ConstPlane, 4> variance{};
    bool variance_of_mean = false;
    std::array<ConstPlane, 4> bc_mean{};
    std::array<ConstPlane, 4> bc_variance{};
    std::array<ConstPlane, 4> bc_moment3{};
    std::array<ConstPlane, 4> moment3{};
    std::array<ConstPlane, 4> moment4{};
    std::array<ConstPlane, 4> bc_moment4{};
    ConstPlane subpixel_u, subpixel_v, subpixel_uu, subpixel_vv, subpixel_uv;
    std::array<ConstPlane, 4> cov_u{}, cov_v{}, bc_cov_u{}, bc_cov_v{};

    bool has_box_cox() const
    {
        return all_of(bc_mean) && all_of(bc_variance) && all_of(bc_moment3);
    }
    /// The untransformed per-pixel variance.
    bool has_variance() const { return all_of(variance); }
    /// M3 and M4 of the untransformed samples, with the variance they extend.
    bool has_moments() const { return all_of(variance) && all_of(moment3) && all_of(moment4); }
    /// M4 of the Box-Cox samples, with the Box-Cox set it extends.
    bool has_box_cox_moment4() const { return has_box_cox() && all_of(bc_moment4); }
    /// The sub-pixel offsets' moments and the untransformed co-moments.
    bool has_positions() const
    {
        return subpixel_u && subpixel_v && subpixel_uu && subpixel_vv && subpixel_uv &&
               all_of(cov_u) && all_of(cov_v);
    }
    /// The Box-Cox co-moments, with the Box-Cox set and the position moments.
    bool has_box_cox_positions() const
    {
        return has_positions() && has_box_cox() && all_of(bc_cov_u) && all_of(bc_cov_v);
    }

private:
    bool all_of(const std::array<ConstPlane, 4>& planes) const
    {
        for (int c = 0; c < channels; ++c)
            if (!planes[c])
                return false;
        return channels > 0;
    }
};

}  // namespace statmc
