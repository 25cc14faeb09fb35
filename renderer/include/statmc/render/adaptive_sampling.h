// Adaptive sampling (docs/sampling.md, "Adaptive sampling"): after each iteration the
// film's statistics are denoised, and the next iteration's samples go where the denoised
// estimate's confidence interval, relative to its value, is widest. A pixel whose own
// mean's interval is narrower than the noise threshold has converged and takes no more
// samples; every other pixel takes at least a minimum rate, so with threshold 0 every
// pixel's count grows without bound and the render stays consistent.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/statistics_image.h"

namespace statmc::render {

struct AdaptiveSettings {
    bool enabled = false;
    /// A pixel has converged when the 95% confidence interval of its own mean is narrower
    /// than ±this fraction of its (denoised) value; 0: none converges, samples only move.
    /// Its own mean's, not the denoised estimate's: the filter's effective sample count
    /// leaves out the bias of averaging, and a stop on it was measured overconfident
    /// (docs/sampling.md).
    double noise_threshold = 0;
    /// Samples per pixel every pixel takes uniformly before adapting, and the fewest a pixel
    /// holds before it may converge: the variance estimates need that many to be trusted.
    int min_spp = 16;
    /// Every pixel that has not converged takes at least this fraction of an adaptive
    /// iteration's samples per pixel (and at least one).
    double min_rate = 0.25;
    /// No pixel takes more than this many times an iteration's samples per pixel.
    double max_rate = 8;
    /// How the allocation map denoises the film: the core filter with the firefly guard.
    DenoiseOptions filter;

    /// Empty when valid, else a message naming the offending setting.
    std::string validate() const;
    /// One line for a checkpoint's identity: resuming must continue the same allocation.
    std::string text() const;
};

/// How many samples each pixel (scanline order) takes in the next iteration.
struct SampleAllocation {
    std::vector<std::uint32_t> counts;
    std::uint64_t total = 0;
    std::size_t converged = 0;  ///< pixels that take none: their interval meets the threshold
};

/// Per pixel, the relative variance of one sample, r = max over channels of
/// s² / (μ̂² + 0.01) (s² the pixel's sample variance, μ̂ the denoised mean; relMSE's 0.01,
/// docs/evaluation.md, so dark pixels are judged by absolute error), for the pixel's own
/// mean (`own`) and for its denoised estimate (`denoised`: divided by g = N/n ≥ 1, the
/// filter's gain, N its effective sample count, n the pixel's own). Each map then holds the
/// largest r of each 3×3 block: a pixel whose few samples have all missed a rare path
/// borrows its neighbours' variance. The relative 95% interval of n samples is
/// ±1.96·sqrt(r/n).
struct RelativeVariance {
    std::vector<float> own, denoised;
};
RelativeVariance relative_variance(const StatisticsImage<3>& stats, const DenoiseOptions& filter,
                                   int threads = 0);

/// The next iteration's counts: `spp` samples per pixel for every pixel that has not
/// converged (by `own`), spread over them so that Σ r/(n + a) is least for r = `denoised`
/// (each count n + a in proportion to sqrt(r), the optimum for independent pixels), within
/// [min_rate·spp, max_rate·spp].
/// Fractions are carried along the scanline, so the counts are deterministic and add up to
/// the budget unless the bounds leave some of it unspent.
SampleAllocation allocate_samples(const RelativeVariance& relative_variance,
                                  const StatisticsImage<3>& stats, int spp,
                                  const AdaptiveSettings& settings);

}  // namespace statmc::render
