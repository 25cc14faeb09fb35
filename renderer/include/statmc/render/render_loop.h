// The progressive render (docs/method.md §6): iterations of 4, 4, 8, 16, ... samples per pixel
// (totals 4, 8, 16, 32, ...), each over 16x16 tiles in parallel (TBB). Samples go straight
// into core's per-pixel accumulators (StatisticsImage<3>): a tile owns its pixels and
// adds their samples in sample-index order, so the statistics are exact and identical
// for any thread count without a merge step. Guides are averaged alongside, and so are
// the per-bounce statistics of ACRR and SMIS (bounce_statistics.h): after each iteration
// but the last they are denoised, and the estimates steer the next iteration's samples.
// Adaptive sampling (adaptive_sampling.h) steers in the same place: from the film's
// denoised beauty it decides how many samples each pixel takes in the next iteration.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "statmc/render/adaptive_sampling.h"
#include "statmc/render/camera.h"
#include "statmc/render/film.h"
#include "statmc/render/integrator.h"
#include "statmc/render/scene.h"

namespace statmc::render {

/// Per-iteration sample counts reaching `total_spp` (the last one clipped).
std::vector<int> schedule_for_spp(int total_spp);
/// Samples per pixel of a whole schedule.
std::uint64_t schedule_samples(const std::vector<int>& schedule);
/// The first `iterations` entries of the schedule: totals 4·2^(K−1).
std::vector<int> schedule_for_iterations(int iterations);

/// The per-bounce quantities a render with `settings` needs: L_0..L_B for ACRR, the win
/// counts of M vertices for SMIS; with `record_all`, both whatever the modes (to inspect
/// them in the EXR).
BounceLayout bounce_layout_for(const IntegratorSettings& settings, bool record_all = false);

/// The per-bounce layers a file of a render with `settings` carries: every quantity with
/// `bounce_layers` (--bounce-layers), else none (steering keeps its own, compact).
BounceLayout bounce_layers_for(const IntegratorSettings& settings, bool bounce_layers);

/// The filter that denoises the per-bounce estimates ACRR and SMIS steer by.
inline DenoiseOptions estimates_filter()
{
    DenoiseOptions o = DenoiseOptions::paper();
    o.radius = 10;
    return o;
}

struct RenderSettings {
    int width = 0, height = 0;
    std::vector<int> schedule;  ///< samples per pixel of each iteration
    std::uint64_t seed = 0;
    int threads = 0;  ///< 0: all cores
    IntegratorSettings integrator;
    /// How the per-bounce statistics are denoised: the paper's filter, without the firefly
    /// guard, at radius 10, where it costs half the time of radius 20 for estimates that
    /// steer as well (docs/sampling.md, "The per-bounce filter's radius").
    DenoiseOptions bounce_filter = estimates_filter();
    bool progress = false;
    /// The index of the first sample every pixel's stream draws: a farm task's share of
    /// the frame starts here (docs/farm.md). Sample s of pixel p is the same for any split.
    std::uint64_t first_sample = 0;
    /// Samples per pixel the film already holds (a resumed checkpoint): the schedule
    /// carries on after them, as if it had never stopped.
    std::uint64_t samples_done = 0;
    /// > 0: the render goes in passes of about a quarter of this many seconds, 5 s at most (whole
    /// iterations when ACRR/SMIS steer), stops only between passes, and calls the
    /// checkpoint callback when this many seconds have passed since the last one and when
    /// it stops early.
    double checkpoint_seconds = 0;
    /// The camera of the previous frame of a sequence: with it, and a film that tracks
    /// motion, each sample adds the screen-space offset from where its first hit is to where
    /// that point was seen in the previous frame (the motion layer, docs/exr-layers.md).
    const Camera* previous_camera = nullptr;
    /// Off: every pixel takes each iteration's samples. On: once every pixel holds
    /// adaptive.min_spp samples, an iteration of s samples per pixel spends s × (pixels
    /// not converged) samples where the denoised estimate is least certain.
    AdaptiveSettings adaptive;
};

/// What one progressive iteration cost.
struct IterationStats {
    int spp = 0;
    double denoise_seconds =
        0;  ///< denoising the estimates it steered by, before rendering (0 without)
    std::uint64_t samples = 0;  ///< camera samples taken, all pixels
};

struct RenderStats {
    double seconds = 0;
    int iterations_done = 0;
    bool interrupted = false;
    bool complete = false;   ///< every sample of the schedule was taken, or every pixel converged
    bool converged = false;  ///< adaptive sampling stopped early: every pixel met the threshold
    std::uint64_t samples = 0;
    std::uint64_t tile_cycles = 0;  ///< time stamp counter cycles inside tiles, all threads
    /// Of tile_cycles, those spent turning samples into per-bounce quantities and adding
    /// them to their statistics (ACRR/SMIS); counted when the scene profiles.
    std::uint64_t bounce_cycles = 0;
};

/// Runs after an iteration with the film so far and what the iteration cost.
using IterationCallback = std::function<void(int iteration, const Film&, const IterationStats&)>;
/// Runs at a pass boundary with the film and the samples per pixel it holds (counted from
/// RenderSettings::first_sample): the hook that writes a checkpoint.
using CheckpointCallback = std::function<void(const Film&, std::uint64_t samples_done)>;

/// Renders into `film`. When `cancel` becomes true, the iteration in progress finishes
/// the tiles already started and skips the rest (never during the first iteration, so
/// every pixel has samples), then the render stops. `after_iteration` runs after each
/// iteration (the hook for per-iteration denoising). The film's steering layout must be
/// bounce_layout_for(settings.integrator) or a superset of it. With
/// settings.checkpoint_seconds, a cancel stops the render at the next pass boundary
/// instead, in any iteration, after `checkpoint` has saved the film.
RenderStats render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                   Film& film, const std::atomic<bool>* cancel = nullptr,
                   const IterationCallback& after_iteration = {},
                   const CheckpointCallback& checkpoint = {});

}  // namespace statmc::render
