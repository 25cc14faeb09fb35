// One pass of the render loop: the given samples of every pixel, tile by tile in
// parallel, into the film (its statistics, per-bounce layers, guides and motion).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "statmc/render/camera.h"
#include "statmc/render/film.h"
#include "statmc/render/integrator.h"
#include "statmc/render/progress.h"
#include "statmc/render/render_loop.h"

namespace statmc::render::detail {

/// What a pass reads and writes.
struct TilePass {
    const PathIntegrator& integrator;
    const Camera& camera;
    const RenderSettings& settings;
    Film& film;
    const BounceEstimates* estimates;  ///< null: nothing steers (the first iteration)
    Progress& progress;
    bool profiling;  ///< count the per-bounce bookkeeping's cycles
};

struct PassCounts {
    std::uint64_t samples = 0, tile_cycles = 0, bounce_cycles = 0;
};

/// Samples [first, first + spp) of every pixel, tile by tile; with `counts` (adaptive
/// sampling), pixel p's next counts[p] samples instead, its stream carrying on from the
/// samples it holds. A skippable pass leaves out the tiles not yet started once `cancel`
/// is set.
PassCounts render_pass(const TilePass& pass, std::uint64_t first, int spp,
                       const std::vector<std::uint32_t>* counts, const std::atomic<bool>* cancel,
                       bool skippable);

}  // namespace statmc::render::detail
