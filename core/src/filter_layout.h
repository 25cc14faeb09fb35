// The padded planes and window tables the filter kernel reads: built once per call by
// filter.cpp, shared read-only by every thread and instruction set.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "statmc/core/filter.h"
#include "statmc/core/firefly_guard.h"

namespace statmc::detail {

/// Padding around the image makes every window read in bounds: padded pixels have
/// threshold −∞ (never members), test mean 0 and value 0.
struct FilterLayout {
    int width = 0, height = 0, channels = 0;
    // The leading channels whose values are averaged and written out; the rest (context
    // channels, context_channel.h) only take part in the test. Only these are written
    // out, on the CPU and the GPU.
    int averaged = 0;
    int pad_x = 0, pad_y = 0;        // the window never reaches further than the image
    std::ptrdiff_t stride = 0;       // floats per padded row
    std::size_t plane_size = 0;      // floats per padded plane
    std::size_t storage_floats = 0;  // all planes together (what a GPU copy takes)
    struct Release {
        void operator()(float* p) const;
    };
    std::unique_ptr<float[], Release> storage;  // all padded planes, back to back (page_memory)

    // Pointers to pixel (0, 0) inside the padding.
    const float* mean[kMaxEstimatorChannels] = {};  // μ̃, the tested quantity
    const float* threshold[kMaxEstimatorChannels] =
        {};                              // T = γ²(df = 2n − 2)·v, or −∞ when untestable
    const float* noise = nullptr;        // the level a neighbour presents (firefly_guard.h)
    const float* noise_limit = nullptr;  // the largest level a centre accepts
    const float* noise_own = nullptr;    // the level a centre presents to the mutual guard
    const float* noise_mutual = nullptr;  // the largest own level a neighbour lets through
    // Per output row and chunk of `lanes` pixels: 1 where some window pixel's level may
    // exceed some centre's limit, so the kernel must test the guard there. Elsewhere —
    // nearly everywhere — it runs without the extra compare.
    int lanes = 1, chunks = 0;
    std::vector<std::uint8_t> guarded;
    bool needs_guard(int y, int chunk) const
    {
        return guarded[std::size_t(y) * chunks + chunk] != 0;
    }
    // Per output row and chunk: 0 where the call wants none of its pixels (PixelMask), and
    // the kernel skips it. Empty: every chunk is computed.
    std::vector<std::uint8_t> wanted;
    bool computes(int y, int chunk) const
    {
        return wanted.empty() || wanted[std::size_t(y) * chunks + chunk] != 0;
    }
    const float* value[kMaxEstimatorChannels] = {};  // F, what is averaged
    const float* inverse_count = nullptr;            // 1/n (0 in the padding), for diagnostics only
    int guide_count = 0;                             // 0, 3 (albedo or normal) or 6 (both)
    const float* guide[6] = {};  // scaled by √(log2 e)/(√2·σ): −Σ (Δg)² is the log2-weight
    // With the guides' variances (else null): u = Σ_guides (scale² · s²/n), the part of
    // E[Σ (Δg)²] a pixel's own guide noise adds. The log2-weight is then
    // spatial − max(0, Σ (Δg)² − 2·min(u_i, u_j)) (docs/method.md §5, guide noise).
    const float* guide_noise = nullptr;

    // The window walked: rows |dy| ≤ reach_y, and in row dy the columns
    // inner_half_width[dy] < |dx| ≤ half_width[dy] (index dy + pad_y; −1 where the row is
    // outside that disk). A plain filter walks its disk less the centre (inner radius 0);
    // the radius ladder walks one annulus per rung (set_window). Spatial weight and its
    // base-2 logarithm at (dx, dy) are at [(dy + pad_y)*(2*pad_x+1) + dx + pad_x], for the
    // whole disk of the layout's radius.
    int reach_y = 0;
    std::vector<int> half_width;
    std::vector<int> inner_half_width;
    std::vector<float> spatial_weight;
    std::vector<float> spatial_log2_weight;
    // 2^spatial_log2_weight by the kernel's own exp2 (FilterKernel::exp2): the guided weight
    // of a tap whose guides agree exactly, as on a flat wall. The kernel takes it from here
    // instead of computing the exp, and gets the same bits (docs/filter-design.md).
    std::vector<float> flat_guide_weight;

    // The radius ladder's running sums (filter_rungs): planes of Σ W(F_j − F_i) per channel,
    // Σ W, the member count and Σ W²/n, `stride` floats per row. When set, each pixel's sums
    // are stored there after a call, and start from them when carry_from_previous.
    static constexpr int kCarryPlanes = 7;
    float* carry[kCarryPlanes] = {};
    bool carry_from_previous = false;

    float spatial(int dx, int dy) const { return spatial_weight[table_index(dx, dy)]; }
    float spatial_log2(int dx, int dy) const { return spatial_log2_weight[table_index(dx, dy)]; }
    float flat_guide(int dx, int dy) const { return flat_guide_weight[table_index(dx, dy)]; }
    std::size_t table_index(int dx, int dy) const
    {
        return std::size_t(dy + pad_y) * (2 * pad_x + 1) + (dx + pad_x);
    }
};

/// Filters output rows [y0, y1), chunks of kernel-width columns [chunk0, chunk1).
using FilterRowsFn = void (*)(const FilterLayout& layout, const std::vector<Plane>& out,
                              const FilterDiagnostics& diagnostics, int y0, int y1, int chunk0,
                              int chunk1);

/// One instruction set's build of the kernel (filter_scalar.cpp, filter_avx2.cpp,
/// filter_avx512.cpp).
struct FilterKernel {
    int lanes = 1;  // its SIMD width, which sets the layout's chunks
    FilterRowsFn rows = nullptr;
    /// 2^x for x ≤ 0, element by element, with the very arithmetic `rows` uses.
    void (*exp2)(const float* x, float* out, std::size_t n) = nullptr;
};
FilterKernel filter_kernel_scalar();
FilterKernel filter_kernel_avx2();
FilterKernel filter_kernel_avx512();
/// The build for `level`, which must be resolved (not Auto) and run on this CPU.
FilterKernel filter_kernel(SimdLevel level);

/// The firefly guard's levels for `est` under `options` (empty where the guard does not
/// apply).
NoiseLevels guard_levels(const EstimatorImage& est, const DenoiseOptions& options);

/// The layout `kernel` reads. `with_inverse_count` adds the 1/n plane the effective sample
/// count needs. `noise`: guard_levels(est, options).
FilterLayout make_filter_layout(const EstimatorImage& est, const Guides& guides,
                                const DenoiseOptions& options, const NoiseLevels& noise,
                                int nthreads, const FilterKernel& kernel,
                                bool with_inverse_count = false);

/// Marks the chunks holding a pixel of `mask` (empty: all of them) in layout.wanted.
void set_wanted(FilterLayout& layout, const PixelMask& mask);

/// Makes the layout walk the annulus inner < |d| ≤ outer (radii ≤ the layout's own; inner
/// 0 is the whole disk less the centre).
void set_window(FilterLayout& layout, int outer, int inner);

/// filter() at each radius of `radii` (ascending, in [1, options.radius]) from one layout:
/// each rung adds only its annulus to the previous rung's sums, so the ladder costs one
/// pass of the largest radius. After each rung, `out` and `diagnostics` hold that rung's
/// result and `rung_done(radius)` is called (serially). A rung sums its taps in another
/// order than filter() at its radius, so it agrees with it to float rounding; bitwise the
/// same for any thread count. `wanted`: empty, or one PixelMask per rung, each a subset of
/// the one before (a pixel's sums carry from rung to rung).
void filter_rungs(const EstimatorImage& est, const Guides& guides, const DenoiseOptions& options,
                  const std::vector<int>& radii, const std::vector<Plane>& out,
                  const FilterDiagnostics& diagnostics, int nthreads, SimdLevel level,
                  const std::function<void(int radius)>& rung_done,
                  const std::vector<PixelMask>& wanted = {});

/// The channel counts the kernels are built for: 1 to 4, and 6, 9 and 12 (joint AOVs).
constexpr bool kernel_takes_channels(int channels)
{
    return (channels >= 1 && channels <= 4) || channels == 6 || channels == 9 || channels == 12;
}

}  // namespace statmc::detail
