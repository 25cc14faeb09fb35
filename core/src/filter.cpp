#include "statmc/core/filter.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "filter_cuda.h"
#include "filter_layout.h"
#include "statmc/core/cuda_device.h"
#include "statmc/core/thread_limit.h"

namespace statmc {

namespace {

SimdLevel hardware_simd_level()
{
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f"))
        return SimdLevel::Avx512;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return SimdLevel::Avx2;
    return SimdLevel::Scalar;
}

/// $STATMC_SIMD lowers the level (never raises it past what the CPU runs).
SimdLevel requested_cap()
{
    const char* env = std::getenv("STATMC_SIMD");
    if (!env || !*env)
        return SimdLevel::Avx512;
    for (SimdLevel level : {SimdLevel::Scalar, SimdLevel::Avx2, SimdLevel::Avx512})
        if (std::strcmp(env, simd_level_name(level)) == 0)
            return level;
    std::fprintf(stderr, "statmc: ignoring STATMC_SIMD=%s (expected scalar, avx2 or avx512)\n",
                 env);
    return SimdLevel::Avx512;
}

}  // namespace

SimdLevel detected_simd_level()
{
    static const SimdLevel level = std::min(hardware_simd_level(), requested_cap());
    return level;
}

std::vector<SimdLevel> supported_simd_levels()
{
    std::vector<SimdLevel> levels;
    for (SimdLevel level : {SimdLevel::Scalar, SimdLevel::Avx2, SimdLevel::Avx512})
        if (level <= hardware_simd_level())
            levels.push_back(level);
    return levels;
}

const char* simd_level_name(SimdLevel level)
{
    switch (level) {
    case SimdLevel::Auto:
        return "auto";
    case SimdLevel::Scalar:
        return "scalar";
    case SimdLevel::Avx2:
        return "avx2";
    case SimdLevel::Avx512:
        return "avx512";
    }
    return "?";
}

SimdLevel usable_simd_level(SimdLevel level)
{
    if (level == SimdLevel::Auto)
        return detected_simd_level();
    if (level > hardware_simd_level())
        throw std::invalid_argument(std::string("this CPU cannot run the ") +
                                    simd_level_name(level) + " kernel");
    return level;
}

namespace detail {
FilterKernel filter_kernel(SimdLevel level)
{
    switch (level) {
    case SimdLevel::Avx512:
        return filter_kernel_avx512();
    case SimdLevel::Avx2:
        return filter_kernel_avx2();
    default:
        return filter_kernel_scalar();
    }
}
}  // namespace detail

bool filter_takes_channels(int channels) { return detail::kernel_takes_channels(channels); }

void require_mask_fits(const PixelMask& mask, int width, int height)
{
    if (!mask.empty() && mask.size() != std::size_t(width) * std::size_t(height))
        throw std::invalid_argument("the pixel mask has " + std::to_string(mask.size()) +
                                    " entries for a " + std::to_string(width) + "x" +
                                    std::to_string(height) + " image");
}

PixelMask grown_mask(const PixelMask& mask, int width, int height, int radius)
{
    // Across the rows, then down the columns: the box is the two spans' product.
    PixelMask rows(mask.size()), out(mask.size());
    tbb::parallel_for(0, height, [&](int y) {
        const std::uint8_t* in = mask.data() + std::size_t(y) * width;
        std::uint8_t* row = rows.data() + std::size_t(y) * width;
        for (int x = 0; x < width; ++x)
            for (int t = std::max(0, x - radius); t <= std::min(width - 1, x + radius); ++t)
                if (in[t]) {
                    row[x] = 1;
                    break;
                }
    });
    tbb::parallel_for(0, height, [&](int y) {
        std::uint8_t* row = out.data() + std::size_t(y) * width;
        for (int t = std::max(0, y - radius); t <= std::min(height - 1, y + radius); ++t) {
            const std::uint8_t* in = rows.data() + std::size_t(t) * width;
            for (int x = 0; x < width; ++x)
                row[x] |= in[x];
        }
    });
    return out;
}

namespace {

void check_arguments(const EstimatorImage& est, const DenoiseOptions& options,
                     const std::vector<Plane>& out)
{
    if (const std::string why = options.validate(); !why.empty())
        throw std::invalid_argument(why);
    if (!filter_takes_channels(est.channels))
        throw std::invalid_argument("the filter takes 1 to 4, 6, 9 or 12 channels, got " +
                                    std::to_string(est.channels));
    if (est.width <= 0 || est.height <= 0)
        throw std::invalid_argument("the image is empty");
    const int averaged = est.channels - est.context_channels;
    if (int(out.size()) < averaged)
        throw std::invalid_argument("fewer output planes than channels");
    for (int c = 0; c < averaged; ++c)
        if (!out[c])
            throw std::invalid_argument("null output plane");
}

}  // namespace

namespace {

detail::FilterKernel checked_kernel(SimdLevel level)
{
    return detail::filter_kernel(usable_simd_level(level));
}

// Runs the kernel over the whole image. Tiles of a few rows by 64 columns keep the
// window's planes in L2. Tiles start at multiples of kTileRows, so the kernel's paired
// centre rows (filter_kernel.h) pair up in every tile; a split range of 3 rows would run
// one of them alone, at nearly twice its cost. Each pixel is computed alone, so the tiling
// cannot change the result.
void run_kernel(detail::FilterRowsFn rows, const detail::FilterLayout& layout, int height,
                const std::vector<Plane>& out, const FilterDiagnostics& diagnostics)
{
    constexpr int kTileRows = 4;
    const int chunk_grain = std::max(1, 64 / layout.lanes);
    const int row_tiles = (height + kTileRows - 1) / kTileRows;
    tbb::parallel_for(
        tbb::blocked_range2d<int>(0, row_tiles, 1, 0, layout.chunks, chunk_grain),
        [&](const tbb::blocked_range2d<int>& r) {
            rows(layout, out, diagnostics, r.rows().begin() * kTileRows,
                 std::min(height, r.rows().end() * kTileRows), r.cols().begin(), r.cols().end());
        },
        tbb::simple_partitioner());
}

// Whether options.device sends this image to the GPU (docs/gpu.md).
bool on_cuda(const EstimatorImage& est, const DenoiseOptions& options)
{
    switch (options.device) {
    case Device::Cpu:
        return false;
    case Device::Auto:
        return est.pixels() >= kAutoCudaPixels && cuda_available();
    case Device::Cuda:
        break;
    }
    std::string why;
    if (!cuda_available(&why))
        throw std::runtime_error("device=cuda: " + why);
    return true;
}

// The GPU loaded with `layout` when on_cuda() chose it, else null for the CPU. device=cuda
// reports what fails (too little memory, a radius beyond the GPU's shared memory); auto
// takes the CPU instead.
std::unique_ptr<detail::CudaFilter> gpu_for(const detail::FilterLayout& layout,
                                            const DenoiseOptions& options, bool chosen, bool carry)
{
    if (!chosen)
        return nullptr;
    if (options.device == Device::Cuda)
        return std::make_unique<detail::CudaFilter>(layout, carry);
    try {
        return std::make_unique<detail::CudaFilter>(layout, carry);
    } catch (const std::runtime_error&) {
        return nullptr;
    }
}

}  // namespace

void filter(const EstimatorImage& est, const Guides& guides, const DenoiseOptions& options,
            const std::vector<Plane>& out, const FilterDiagnostics& diagnostics, int nthreads,
            SimdLevel level, const PixelMask& wanted)
{
    check_arguments(est, options, out);
    const bool gpu = on_cuda(est, options);
    const detail::FilterKernel kernel = checked_kernel(level);
    run_with_threads(nthreads, [&] {
        detail::FilterLayout layout =
            detail::make_filter_layout(est, guides, options, detail::guard_levels(est, options),
                                       nthreads, kernel, diagnostics.any());
        detail::set_wanted(layout, wanted);
        if (const auto device = gpu_for(layout, options, gpu, false))
            device->run(layout, out, diagnostics);
        else
            run_kernel(kernel.rows, layout, est.height, out, diagnostics);
    });
}

namespace detail {
void filter_rungs(const EstimatorImage& est, const Guides& guides, const DenoiseOptions& options,
                  const std::vector<int>& radii, const std::vector<Plane>& out,
                  const FilterDiagnostics& diagnostics, int nthreads, SimdLevel level,
                  const std::function<void(int radius)>& rung_done,
                  const std::vector<PixelMask>& wanted)
{
    check_arguments(est, options, out);
    for (std::size_t k = 0; k < radii.size(); ++k)
        if (radii[k] < 1 || radii[k] > options.radius || (k > 0 && radii[k] <= radii[k - 1]))
            throw std::invalid_argument("filter rungs: radii must ascend within [1, radius]");
    if (!wanted.empty() && wanted.size() != radii.size())
        throw std::invalid_argument("filter rungs: one pixel mask per rung, or none");
    const bool gpu = on_cuda(est, options);
    const FilterKernel kernel = checked_kernel(level);
    run_with_threads(nthreads, [&] {
        FilterLayout layout = make_filter_layout(est, guides, options, guard_levels(est, options),
                                                 nthreads, kernel, diagnostics.any());
        // The running sums: on the GPU they stay in device memory between rungs.
        std::vector<float> sums;
        const std::unique_ptr<CudaFilter> device = gpu_for(layout, options, gpu, true);
        if (!device) {
            sums.resize(FilterLayout::kCarryPlanes * layout.stride * std::size_t(est.height));
            for (int k = 0; k < FilterLayout::kCarryPlanes; ++k)
                layout.carry[k] = sums.data() + k * layout.stride * std::size_t(est.height);
        }
        int inner = 0;
        for (std::size_t k = 0; k < radii.size(); ++k) {
            const int radius = radii[k];
            set_window(layout, radius, inner);
            if (!wanted.empty())
                set_wanted(layout, wanted[k]);
            layout.carry_from_previous = inner > 0;
            if (device)
                device->run(layout, out, diagnostics);
            else
                run_kernel(kernel.rows, layout, est.height, out, diagnostics);
            rung_done(radius);
            inner = radius;
        }
    });
}
}  // namespace detail

}  // namespace statmc
