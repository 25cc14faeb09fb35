// The filter kernel on a CUDA GPU (core/cuda/filter_cuda.cu; docs/gpu.md). It reads the
// same padded layout as the CPU kernels, built once on the host: the thresholds, the
// firefly guard's levels and the scaled guides are the CPU's own floats, so the membership
// test decides exactly as on the CPU; only the order of the weighted sums differs.
#pragma once

#include <memory>
#include <vector>

#include "filter_layout.h"

namespace statmc::detail {

/// Milliseconds of the last run, from CUDA events.
struct CudaTimings {
    float upload_ms = 0;    ///< the layout's planes, host to device (once per CudaFilter)
    float kernel_ms = 0;    ///< the last run's kernel
    float download_ms = 0;  ///< the last run's outputs, device to host
};

class CudaFilter {
public:
    /// Uploads `layout`'s planes and tables. `carry`: keep each pixel's sums on the device
    /// between runs (the radius ladder's rungs). Throws std::runtime_error naming the CUDA
    /// call and its error (no device, out of memory, ...).
    CudaFilter(const FilterLayout& layout, bool carry);
    ~CudaFilter();
    CudaFilter(const CudaFilter&) = delete;
    CudaFilter& operator=(const CudaFilter&) = delete;

    /// Runs the layout's current window (set_window) and writes `out` and `diagnostics` as
    /// the CPU kernels do. With carry, starts from the previous run's sums when
    /// `layout.carry_from_previous`.
    void run(const FilterLayout& layout, const std::vector<Plane>& out,
             const FilterDiagnostics& diagnostics);

    CudaTimings timings() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace statmc::detail
