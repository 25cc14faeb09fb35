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
/// the Box-Cox ones (docs/method.md §10).
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
