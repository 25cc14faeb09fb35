// A statmc-render job: the frames of one invocation, each rendered whole, as one farm task
// or as N tasks merged, with checkpoints, its statistics EXR (and the denoised one) written,
// and the report. renderer/cmd/main.cpp fills it from the command line, as pbrt-v4's cmd/
// calls into its library.
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "statmc/render/bounce_layout.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/render_task.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_description.h"

namespace statmc::render {

/// One frame to render: its output file, its time, its seed and its number (none for a
/// still).
struct FrameToRender {
    std::string output;
    double time = 0;
    int seed = 0;
    std::optional<int> number;
};

struct RenderJob {
    std::string scene_path;
    SceneDescription scene;
    /// Resolution, schedule, integrator, adaptive sampling, threads, progress; the seed is
    /// each frame's.
    RenderSettings settings;
    bool bounce_layers = false;  ///< every per-bounce layer, not only those steering uses
    bool higher_moments = false;  ///< also write M3, M4, boxcoxM4 (OutputInfo::higher_moments)
    std::vector<FrameToRender> frames;
    double fps = 24;
    RenderTask task;          ///< the farm task; 0/1 for the whole frame
    bool whole_frame = true;  ///< no --task and no --tasks: the header names no task
    int tasks = 0;            ///< > 0: the frame as that many tasks in turn, merged
    double checkpoint_seconds = 0;
    bool resume = false;
    bool denoise = false;          ///< also write OUT.denoised.exr
    bool every_iteration = false;  ///< rewrite the outputs after every iteration
    bool quiet = false;
    bool profile = false;
};

/// What else, besides scene, seed, resolution and task, makes two renders' films
/// incompatible: a checkpoint's settings line.
std::string settings_text(const RenderSettings& s, bool bounce_layers);

/// Renders every frame of `job` from `scene` (built from job.scene) and writes its outputs;
/// reports on stderr (and, with `profile`, stdout). Returns the process's exit status: 0,
/// or 130 when `interrupted` (SIGINT, SIGTERM) stopped it before a frame was whole. Throws
/// on errors.
int run_render_job(const RenderJob& job, const Scene& scene, const std::atomic<bool>& interrupted);

}  // namespace statmc::render
