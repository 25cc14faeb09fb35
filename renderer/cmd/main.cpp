// statmc-render: renders a pbrt-v3 scene with statmc's path tracer and writes the
// per-pixel statistics EXR (docs/exr-layers.md), optionally denoised as well.
#include <atomic>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>

#include "statmc/layers/atomic_file.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/frame_names.h"

#include "option_checks.h"
#include "sampling_options.h"
#include "statmc/render/progress.h"
#include "statmc/render/render_job.h"
#include "statmc/render/render_task.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"

namespace {

std::atomic<bool> g_interrupted{false};

// SIGINT or SIGTERM. Async-signal-safe: sets a lock-free flag; a second signal ends the
// process at once, removing the temporary of a write in progress.
extern "C" void on_interrupt(int signal_number)
{
    g_interrupted.store(true);
    std::signal(signal_number, statmc::layers::remove_temporaries_and_end);
}

/// "WxH" (or "WXH") with decimal W and H and nothing else; false otherwise.
bool parse_resolution(const std::string& text, int& width, int& height)
{
    const char* end = text.data() + text.size();
    const auto w = std::from_chars(text.data(), end, width);
    if (w.ec != std::errc() || w.ptr == text.data() || w.ptr == end ||
        (*w.ptr != 'x' && *w.ptr != 'X'))
        return false;
    const auto h = std::from_chars(w.ptr + 1, end, height);
    return h.ec == std::errc() && h.ptr == end && h.ptr != w.ptr + 1;
}

// The frames --frame/--frames ask for (one still without them). A frame's seed mixes the
// frame number into --seed (layers::frame_seed), so that the frames of a sequence have
// independent noise, and its header says which seed it drew with.
std::vector<statmc::render::FrameToRender> frames_to_render(const std::string& output,
                                                            const std::string& list, bool one_frame,
                                                            int frame, double fps, int seed)
{
    if (list.empty() && !one_frame)
        return {{output, 0.0, seed, std::nullopt}};
    std::vector<int> numbers = {frame};
    if (!list.empty()) {
        const auto listed = statmc::layers::frame_list(list);
        if (!listed)
            throw std::runtime_error("--frames: cannot read '" + list +
                                     "' as frames (e.g. 1-24, 1-48x2, 3,5,7; at most " +
                                     std::to_string(statmc::layers::kMaxFrames) + " frames)");
        numbers = *listed;
    }
    const std::string pattern = statmc::layers::frame_pattern(output);
    if (pattern.empty() && numbers.size() > 1)
        throw std::runtime_error("-o " + output +
                                 ": --frames needs a frame pattern in the output name "
                                 "(shot.#.exr, shot.%04d.exr)");
    std::vector<statmc::render::FrameToRender> frames;
    for (int n : numbers) {
        frames.push_back({pattern.empty() ? output : statmc::layers::frame_path(pattern, n),
                          n / fps, statmc::layers::frame_seed(seed, n), n});
    }
    return frames;
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace statmc::render;
    statmc::layers::silence_library_debug_messages();
    statmc::layers::install_write_signal_handlers();
    CLI::App app{"statmc-render: path-trace a pbrt-v3 scene (Embree 3) into a statistics EXR\n"
                 "(mean, variance, Box-Cox moments, sample count, albedo/normal/depth guides)."};
    // The job's own options land in it directly; the rest become its settings below.
    RenderJob job;
    std::string output_option;
    int spp = 0, iterations = 0, seed = 0, threads = 0, maxdepth = -1;
    std::string resolution;
    SamplingOptions sampling;
    statmc::render::AdaptiveSettings adaptive;
    app.add_option("scene", job.scene_path, "pbrt-v3 scene file")->required();
    app.add_option("-o,--output", output_option,
                   "output statistics EXR; with --frame/--frames it may hold a frame pattern "
                   "(shot.#.exr = %04d, shot.%04d.exr)")
        ->required();
    auto* spp_opt = app.add_option("--spp", spp,
                                   "total samples per pixel, in iterations of 4, 4, 8, 16, ... "
                                   "[default: the scene's Sampler pixelsamples]")
                        ->check(integer_at_least(1));
    app.add_option("--iterations", iterations,
                   "number of progressive iterations instead of --spp (totals 4, 8, 16, ...) "
                   "[default: unset]")
        ->check(integer_at_least(1))
        ->excludes(spp_opt);
    app.add_option(
        "--resolution", resolution,
        "image size WxH; the scene's fov is kept [default: the scene's Film resolution]");
    app.add_option("--seed", seed, "random seed")
        ->capture_default_str()
        ->check(integer_at_least(0));
    app.add_option("--threads", threads, "worker threads, 0 = all cores")
        ->capture_default_str()
        ->check(integer_at_least(0));
    app.add_option("--maxdepth", maxdepth,
                   "maximum path depth [default: the scene's Integrator maxdepth]")
        ->check(integer_at_least(0));
    add_sampling_options(app, sampling);
    add_adaptive_options(app, adaptive);
    app.add_flag(
        "--bounce-layers", job.bounce_layers,
        "track every per-bounce quantity (L and win counts) in full statistics and write them "
        "as layers, whatever --rr and --mis [default: none written; ACRR and SMIS keep what "
        "they steer by to themselves]");
    app.add_flag("--higher-moments", job.higher_moments,
                 "also write M3, M4 and boxcoxM4 (docs/exr-layers.md): no statmc stage reads "
                 "them; they merge exactly, for research [default: off]");
    std::string task_text;
    auto* task_opt = app.add_option(
        "--task", task_text,
        "render task I of N (counted from 0): the sample indices floor(I*S/N) .. "
        "floor((I+1)*S/N)-1 of every pixel, for a farm; merge the N outputs with statmc "
        "--merge (docs/farm.md) [default: the whole frame]");
    auto* tasks_opt =
        app.add_option("--tasks", job.tasks,
                       "render the frame as N tasks one after another in this process and write "
                       "their merge: what statmc --merge makes of N --task outputs, bit for bit "
                       "[default: unset]")
            ->check(integer_at_least(1))
            ->excludes(task_opt);
    // Adaptive counts come from the whole frame's statistics, which no task holds.
    app.get_option("--adaptive")->excludes(task_opt)->excludes(tasks_opt);
    app.add_option("--checkpoint", job.checkpoint_seconds,
                   "every SECONDS, at a sample boundary, save the film to OUT.checkpoint "
                   "(atomically); a SIGINT/SIGTERM saves it and stops; removed once OUT is "
                   "written [default: off]")
        ->check(CLI::PositiveNumber)
        ->excludes(tasks_opt);
    app.add_flag("--resume", job.resume,
                 "continue from OUT.checkpoint when it exists (refused when it belongs to "
                 "another scene, seed, resolution, task or settings); start afresh when it does "
                 "not [default: off]")
        ->excludes(tasks_opt);
    app.add_flag("--denoise", job.denoise,
                 "also write the denoised image to OUT.denoised.exr [default: off]");
    app.add_flag(
           "--write-every-iteration", job.every_iteration,
           "rewrite OUT (and OUT.denoised.exr with --denoise) after every progressive iteration, "
           "each time atomically, to watch the render refine [default: off]")
        ->excludes(tasks_opt);
    int frame = 0;
    std::string frames_text;
    auto* frame_opt = app.add_option(
        "--frame", frame,
        "render frame F of a sequence: the camera at time F/fps (ActiveTransform and "
        "TransformTimes animate it), the seed mixed with F, and the motion layer (motion.X/Y: "
        "where each pixel's first hit was in frame F-1, in pixels) [default: a still]");
    auto* frames_opt =
        app.add_option("--frames", frames_text,
                       "render these frames one after another, each as --frame would (1-24, "
                       "1-48x2, 3,5,7); -o must hold a frame pattern [default: a still]")
            ->excludes(frame_opt);
    app.add_option("--fps", job.fps, "frames per second of --frame/--frames")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    for (CLI::Option* sequence : {frame_opt, frames_opt})
        sequence->excludes(tasks_opt)
            ->excludes(task_opt)
            ->excludes("--checkpoint")
            ->excludes("--resume")
            ->excludes("--write-every-iteration");
    bool validate = false;
    app.add_flag("--validate", validate,
                 "read the scene and check every option, then exit without rendering (what "
                 "statmc-farm submit runs before it submits) [default: off]");
    app.add_flag("-q,--quiet", job.quiet, "no progress bar and no summary [default: off]");
    app.add_flag("--profile", job.profile,
                 "print samples/s, rays/s and the share of render time spent in Embree traversal "
                 "(the rest is shading, sampling and accumulation) [default: off]");
    CLI11_PARSE(app, argc, argv);

    try {
        {  // Fail before rendering, not after, when the output cannot be written.
            const std::filesystem::path out(output_option);
            const auto dir = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
            if (!std::filesystem::is_directory(dir))
                throw std::runtime_error(output_option + ": cannot write: directory '" +
                                         dir.string() + "' does not exist");
        }
        const std::vector<FrameToRender> frames = frames_to_render(
            output_option, frames_text, frame_opt->count() > 0, frame, job.fps, seed);
        const RenderTask task = task_text.empty() ? RenderTask{} : parse_task(task_text);
        SceneDescription desc = parse_scene_file(job.scene_path);
        for (const std::string& w : desc.warnings)
            std::fprintf(stderr, "%s\n", w.c_str());
        int width = desc.camera.width, height = desc.camera.height;
        if (!resolution.empty() && !parse_resolution(resolution, width, height))
            throw std::runtime_error("--resolution: expected WxH, got '" + resolution + "'");
        RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.schedule = iterations > 0 ? schedule_for_iterations(iterations)
                                           : schedule_for_spp(spp > 0 ? spp : desc.spp);
        settings.seed = std::uint64_t(seed);
        settings.threads = threads;
        IntegratorSettings& integrator = settings.integrator;
        integrator.maxdepth = maxdepth >= 0 ? maxdepth : desc.maxdepth;
        sampling.apply(settings);
        settings.adaptive = adaptive;
        if (adaptive.enabled &&
            schedule_samples(settings.schedule) <= std::uint64_t(adaptive.min_spp))
            throw std::runtime_error(
                "--adaptive: " + std::to_string(schedule_samples(settings.schedule)) +
                " samples per pixel leave nothing to adapt: every pixel takes its first " +
                std::to_string(adaptive.min_spp) +
                " uniformly (--adaptive-min-spp); give --spp above that");
        // Before anything is allocated: the same limits for --resolution and the Film.
        require_renderable_resolution(width, height, bounce_layout_for(integrator),
                                      bounce_layers_for(integrator, job.bounce_layers),
                                      resolution.empty() ? desc.film_where : "--resolution");
        settings.progress = !job.quiet && Progress::stderr_is_terminal();

        const int frame_spp = int(schedule_samples(settings.schedule));
        task_samples(frame_spp, job.tasks > 0 ? RenderTask{job.tasks - 1, job.tasks} : task);
        if (validate) {
            std::printf("statmc-render: %s: the scene and options are valid\n",
                        job.scene_path.c_str());
            return 0;
        }

        job.scene = std::move(desc);
        job.settings = settings;
        job.frames = frames;
        job.task = task;
        job.whole_frame = task_text.empty() && job.tasks == 0;
        Scene scene(job.scene);
        scene.enable_profiling(job.profile);
        // SIGTERM is what schedulers send on preemption: it stops the render like Ctrl-C, and
        // what was rendered is written with its true counts (or, checkpointing, saved).
        std::signal(SIGINT, on_interrupt);
        std::signal(SIGTERM, on_interrupt);
        return run_render_job(job, scene, g_interrupted);
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "statmc-render: error: out of memory rendering %s\n",
                     job.scene_path.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "statmc-render: error: %s\n", e.what());
        return 1;
    }
}
