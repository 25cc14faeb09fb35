// A farm job: frames of a scene (or a sequence) rendered as N tasks each by statmc-render
// on a Slurm job array, then merged (and denoised) per frame by statmc once its tasks have
// succeeded (docs/farm.md). This file turns the job into the batch scripts; slurm.h
// submits them.
#pragma once

#include <string>
#include <vector>

namespace statmc::farm {

struct Frame {
    int number = 0;      ///< the frame number (or the scene's position in the list)
    std::string scene;   ///< the pbrt scene file
    std::string output;  ///< the merged statistics EXR
};

/// Slurm options passed through to every job as #SBATCH lines (empty: the cluster's default).
struct SlurmOptions {
    std::string partition, time, mem, account;
    int cpus_per_task = 0;
};

struct FarmJob {
    std::vector<Frame> frames;
    int tasks = 1;             ///< tasks per frame
    int spp = 0;               ///< samples per pixel of each frame (0: the scene's)
    int seed = 0;              ///< mixed with each frame's number (frame_seed)
    double checkpoint_seconds = 60;
    int max_restarts = 3;      ///< requeues of a killed render task before it fails
    bool denoise = false;          ///< also write OUT.denoised.exr
    std::string denoise_modifiers; ///< statmc --denoise modifiers (":method=paper"), "" = default
    std::vector<std::string> render_args;  ///< more statmc-render options, verbatim
    SlurmOptions slurm;
    std::string job_dir;       ///< scripts, logs and the job record
    std::string render_exe, statmc_exe;  ///< absolute paths
};

/// Where task `task` of `frame` writes: "out/shot.0001.exr" -> "out/shot.0001.task2.exr".
std::string task_output(const Frame& frame, int task);
/// The seed every task of `frame` renders with: job.seed mixed with the frame's number, as
/// statmc-render --frames mixes it, so that no two frames share their noise (a temporal
/// denoise over the frames would merge it as if it were more samples).
int frame_seed(const FarmJob& job, const Frame& frame);
/// Where the denoised image of `frame` goes: "out/shot.0001.denoised.exr".
std::string denoised_output(const Frame& frame);

/// The render job array: element k renders task k % N of frame k / N with a checkpoint,
/// resuming from it when Slurm runs the element again, and requeues itself when the
/// render is killed (exit status >= 128), up to max_restarts times.
std::string render_script(const FarmJob& job);
/// The merge job, run once per frame with the frame's index in job.frames as its argument:
/// statmc merges the frame's task outputs in task order (and denoises the merge).
std::string merge_script(const FarmJob& job);

/// A number as the batch scripts write it ("%g": 60, 0.5).
std::string number_text(double value);

/// Single-quoted for a POSIX shell.
std::string shell_quote(const std::string& text);

}  // namespace statmc::farm
