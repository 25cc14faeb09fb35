// Read-only views of per-pixel statistics planes, in the form the EXR layer contract stores.
#pragma once

#include <array>

#include "statmc/core/plane.h"

namespace statmc {

/// Per-pixel statistics of a C-channel quantity. Variances are per sample, s² = M2/(n − 1),
/// unless `variance_of_mean` says the untransformed `variance` planes are already divided
/// by n (renderers' "mse" AOVs); the Box-Cox variance is always per sample. bc_moment3 is the third
/// central moment M3/n of the Box-Cox samples. Box-Cox planes may be absent (renderers
/// that write only a variance AOV).
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

    bool has_box_cox() const
    {
        for (int c = 0; c < channels; ++c)
            if (!bc_mean[c] || !bc_variance[c] || !bc_moment3[c])
                return false;
        return channels > 0;
    }
};

}  // namespace statmc
