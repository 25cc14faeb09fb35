// The StatMC filter (docs/method.md §5): average each pixel with the neighbours whose
// estimators a t-test cannot tell apart from it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/plane.h"

namespace statmc {

/// Optional feature buffers that sharpen the weights; an absent guide has null planes.
struct Guides {
    std::array<ConstPlane, 3> albedo{};
    std::array<ConstPlane, 3> normal{};
    /// Optional, per guide: the per-sample variance of its samples, summed over its three
    /// channels. With it the filter takes the part of a guide distance that the guides' own
    /// sampling noise explains out of the weight (docs/method.md §5, guide noise), so a
    /// pixel on an emitter edge or behind a glossy bounce is not cut off by a noisy guide.
    ConstPlane albedo_variance{};
    ConstPlane normal_variance{};

    bool has_albedo() const { return albedo[0] && albedo[1] && albedo[2]; }
    bool has_normal() const { return normal[0] && normal[1] && normal[2]; }
};

/// Per-pixel diagnostics the filter can write as it goes; null planes are skipped.
struct FilterDiagnostics {
    Plane members;     ///< neighbours that passed the test, the centre included
    Plane weight_sum;  ///< Σ W_ij, the centre's weight 1 included
    /// (Σ W_ij)² / Σ W_ij²/n_j over the members: if each member's mean has variance
    /// σ²/n_j, the output has variance σ²/N, so N is the sample count of one pixel as
    /// precise as the average. Equal weights give M² / Σ 1/n_j (M times the harmonic mean
    /// count), equal weights and counts M·n; 0 when the centre's count is 0.
    Plane effective_samples;

    bool any() const { return members || weight_sum || effective_samples; }
};

/// The pixels a call must compute when not all are needed (verify's fallback): one byte per
/// pixel, row-major over the image, non-zero where wanted. Outputs elsewhere are
/// unspecified; at the wanted pixels they are bitwise those of a call without the mask.
/// Empty: every pixel.
using PixelMask = std::vector<std::uint8_t>;

/// Throws std::invalid_argument ("the pixel mask has N entries for a W×H image") unless
/// `mask` is empty or has one entry per pixel.
void require_mask_fits(const PixelMask& mask, int width, int height);

/// `mask` (width × height, non-empty) grown by `radius` ≥ 0 pixels in every direction: a
/// pixel is set where any pixel of the (2·radius + 1)² box around it is, clipped at the
/// image's edges.
PixelMask grown_mask(const PixelMask& mask, int width, int height, int radius);

/// Instruction sets the filter kernel is built for.
enum class SimdLevel { Auto, Scalar, Avx2, Avx512 };

/// The best level this CPU runs (Avx2 needs AVX2 and FMA; Avx512 needs AVX-512F).
/// $STATMC_SIMD=scalar|avx2|avx512 caps it, for comparisons and for debugging.
SimdLevel detected_simd_level();
/// Every level this CPU runs, Scalar first: what the tests compare against each other.
std::vector<SimdLevel> supported_simd_levels();
const char* simd_level_name(SimdLevel level);
/// `level` with Auto resolved to detected_simd_level(). Throws std::invalid_argument
/// ("this CPU cannot run the avx512 kernel") for a level this CPU does not run.
SimdLevel usable_simd_level(SimdLevel level);

/// Whether filter() takes an image of this many channels: 1 to 4, and 6, 9 or 12 (up to
/// four three-channel layers tested together: joint AOVs).
bool filter_takes_channels(int channels);

/// Filters `est` into `out` (one plane per channel; context channels, which are only tested,
/// take none and any planes given for them are left alone), on the CPU or, by options.device, on a
/// CUDA GPU (docs/gpu.md). Bitwise identical for any thread count. Throws
/// std::invalid_argument on invalid options, a channel count that filter_takes_channels
/// refuses, too few output planes, or an unavailable SIMD level; std::runtime_error when
/// device is Cuda and no GPU can run it (or the image has more than four channels), with
/// the reason.
/// nthreads: 0 = all, 1 = the calling thread only. `wanted`: only those pixels (PixelMask);
/// the kernel skips chunks of its width without one.
void filter(const EstimatorImage& est, const Guides& guides, const DenoiseOptions& options,
            const std::vector<Plane>& out, const FilterDiagnostics& diagnostics = {},
            int nthreads = 0, SimdLevel level = SimdLevel::Auto, const PixelMask& wanted = {});

/// A plain, unoptimised double-precision implementation of docs/method.md §5, the yardstick
/// that the fast filter is tested and benchmarked against. Single-threaded.
void filter_reference(const EstimatorImage& est, const Guides& guides,
                      const DenoiseOptions& options, const std::vector<Plane>& out,
                      const FilterDiagnostics& diagnostics = {});

}  // namespace statmc
