// What the variance filter's disk loop reads (variance_filter.cpp builds it once per call)
// and the SIMD kernels that walk it (variance_filter_kernel.h). The kernels add the same
// products in the same order as the scalar loop, in double, so every level gives the
// scalar loop's bits (docs/filter-design.md, "The variance filter across x").
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace statmc::detail {

/// spatial · e^(−exponent) exactly as std::exp gives it, without the call where the answer
/// is known: e^0 = 1 (flat guides), and e^(−x) rounds to 0 for every x > 745.14 (guides
/// far apart). The call costs ~30 cycles and is most of the guided filter's time.
inline double guide_weight(double spatial, double exponent)
{
    if (exponent == 0)
        return spatial;
    if (exponent > 746)
        return 0;
    return spatial * std::exp(-exponent);
}

/// One tap of the disk: its offset and the spatial part of w_ij.
struct VarianceTap {
    int dx, dy;
    double spatial;
};

struct VarianceLayout {
    int width = 0, height = 0, channels = 0, radius = 0;
    std::size_t pixels = 0;       ///< per channel; every plane below is channel-major
    /// The per-sample s² that is averaged, NaN where it may not be: lend_s2 where the s² is
    /// an estimate (a borrower takes it), prior_s2 where the moderation may use it. The NaN
    /// is the mark: a tap loads one plane, not a value and a flag.
    std::vector<double> lend_s2;
    std::vector<double> prior_s2;
    /// With a test on the means for the prior (prior_z2 > 0): each pixel's mean and the
    /// squared standard error s²/n of that mean (rounded to float), in double so that the
    /// tap loop converts nothing.
    std::vector<double> mean;
    std::vector<double> mean_se2;
    std::vector<VarianceTap> taps;  ///< raster order, the centre left out
    /// Dense copies of the guides present, three planes per group (albedo, then normal),
    /// and each group's 1/(2σ²).
    std::vector<const float*> guide;
    std::vector<float> guide_storage;  ///< what `guide` points into
    double guide_falloff[2] = {0, 0};
    double prior_z2 = 0;  ///< the squared critical value of the prior's test on the means; 0 = none
    bool borrow = false;  ///< VarianceFilterOptions::borrow_without_interval

    int guide_groups() const { return int(guide.size()) / 3; }
    bool interior(int x, int y) const
    {
        return x >= radius && x < width - radius && y >= radius && y < height - radius;
    }
};

/// One pixel's weighted sums per channel: its own s² or, borrowing, its neighbours' (sum),
/// and over every neighbour the moderation may use (prior). They arrive holding the
/// centre's own terms.
struct VarianceSums {
    double sum[4], weight[4], prior_sum[4], prior_weight[4];
};

/// Adds the disk's taps to the sums of `lanes` pixels (x0, y) … (x0 + lanes − 1, y), all
/// interior (their whole disk inside the image).
using VarianceChunkFn = void (*)(const VarianceLayout& layout, int x0, int y, VarianceSums* sums);

struct VarianceKernel {
    int lanes;
    VarianceChunkFn add_disk;
};

VarianceKernel variance_kernel_avx2();
VarianceKernel variance_kernel_avx512();

}  // namespace statmc::detail
