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

#include "statmc/denoise/denoise.h"
#include "statmc/layers/atomic_file.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/frame_names.h"
#include "statmc/layers/layer_names.h"
#include "statmc/merge/merge.h"

#include "option_checks.h"
#include "sampling_options.h"
#include "statmc/render/camera.h"
#include "statmc/render/checkpoint.h"
#include "statmc/render/exr_output.h"
#include "statmc/render/progress.h"
#include "statmc/render/render_loop.h"
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

// What else, besides scene, seed, resolution and task, makes two renders' films
// incompatible: a checkpoint's settings line.
std::string settings_text(const statmc::render::RenderSettings& s, bool bounce_layers)
{
    const auto& i = s.integrator;
    char text[256];
    std::snprintf(text, sizeof text,
                  "maxdepth %d, rr %d/%d/%d, mis %d/%d/%g, estimates radius %d, bounce layers "
                  "%s, %s, schedule",
                  i.maxdepth, int(i.roulette.mode), i.roulette.start_bounce,
                  i.roulette.tracked_bounces, int(i.mis.mode), i.mis.tracked_bounces,
                  double(i.mis.threshold), s.bounce_filter.radius, bounce_layers ? "all" : "used",
                  s.adaptive.text().c_str());
    std::string out = text;
    for (int n : s.schedule)
        out += " " + std::to_string(n);
    return out;
}

// The tasks' images merged in task order: what statmc --merge makes of their files.
OIIO::ImageBuf merge_tasks(const std::vector<OIIO::ImageBuf>& parts)
{
    std::vector<const OIIO::ImageBuf*> pointers;
    for (const OIIO::ImageBuf& p : parts)
        pointers.push_back(&p);
    OIIO::ImageBuf merged = statmc::merge(pointers);
    if (merged.has_error())
        throw std::runtime_error(merged.geterror());
    return merged;
}

// One frame to render: its output file, its time, its seed and its number (none for a
// still).
struct FrameToRender {
    std::string output;
    double time = 0;
    int seed = 0;
    std::optional<int> number;
};

// The frames --frame/--frames ask for (one still without them). A frame's seed mixes the
// frame number into --seed (layers::frame_seed), so that the frames of a sequence have
// independent noise, and its header says which seed it drew with.
std::vector<FrameToRender> frames_to_render(const std::string& output, const std::string& list,
                                            bool one_frame, int frame, double fps, int seed)
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
    std::vector<FrameToRender> frames;
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
    std::string scene_path, output_option;
    int spp = 0, iterations = 0, seed = 0, threads = 0, maxdepth = -1;
    std::string resolution;
    bool denoise = false, quiet = false, profile = false, every_iteration = false,
         bounce_layers = false;
    SamplingOptions sampling;
    statmc::render::AdaptiveSettings adaptive;
    app.add_option("scene", scene_path, "pbrt-v3 scene file")->required();
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
        "--bounce-layers", bounce_layers,
        "track and write every per-bounce layer (L and win counts) even with classic RR and "
        "standard MIS [default: only those --rr/--mis use]");
    std::string task_text;
    int task_total = 0;
    double checkpoint_seconds = 0;
    bool resume = false;
    auto* task_opt = app.add_option(
        "--task", task_text,
        "render task I of N (counted from 0): the sample indices floor(I*S/N) .. "
        "floor((I+1)*S/N)-1 of every pixel, for a farm; merge the N outputs with statmc "
        "--merge (docs/farm.md) [default: the whole frame]");
    auto* tasks_opt =
        app.add_option("--tasks", task_total,
                       "render the frame as N tasks one after another in this process and write "
                       "their merge: what statmc --merge makes of N --task outputs, bit for bit "
                       "[default: unset]")
            ->check(integer_at_least(1))
            ->excludes(task_opt);
    // Adaptive counts come from the whole frame's statistics, which no task holds.
    app.get_option("--adaptive")->excludes(task_opt)->excludes(tasks_opt);
    app.add_option("--checkpoint", checkpoint_seconds,
                   "every SECONDS, at a sample boundary, save the film to OUT.checkpoint "
                   "(atomically); a SIGINT/SIGTERM saves it and stops; removed once OUT is "
                   "written [default: off]")
        ->check(CLI::PositiveNumber)
        ->excludes(tasks_opt);
    app.add_flag("--resume", resume,
                 "continue from OUT.checkpoint when it exists (refused when it belongs to "
                 "another scene, seed, resolution, task or settings); start afresh when it does "
                 "not [default: off]")
        ->excludes(tasks_opt);
    app.add_flag("--denoise", denoise,
                 "also write the denoised image to OUT.denoised.exr [default: off]");
    app.add_flag(
           "--write-every-iteration", every_iteration,
           "rewrite OUT (and OUT.denoised.exr with --denoise) after every progressive iteration, "
           "each time atomically, to watch the render refine [default: off]")
        ->excludes(tasks_opt);
    int frame = 0;
    std::string frames_text;
    double fps = 24;
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
    app.add_option("--fps", fps, "frames per second of --frame/--frames")
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
    app.add_flag("-q,--quiet", quiet, "no progress bar and no summary [default: off]");
    app.add_flag("--profile", profile,
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
        const std::vector<FrameToRender> frames =
            frames_to_render(output_option, frames_text, frame_opt->count() > 0, frame, fps, seed);
        const RenderTask task = task_text.empty() ? RenderTask{} : parse_task(task_text);
        SceneDescription desc = parse_scene_file(scene_path);
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
        require_renderable_resolution(width, height, bounce_layout_for(integrator, bounce_layers),
                                      resolution.empty() ? desc.film_where : "--resolution");
        settings.progress = !quiet && Progress::stderr_is_terminal();

        const int frame_spp = int(schedule_samples(settings.schedule));
        task_samples(frame_spp, task_total > 0 ? RenderTask{task_total - 1, task_total} : task);
        if (validate) {
            std::printf("statmc-render: %s: the scene and options are valid\n",
                        scene_path.c_str());
            return 0;
        }

        Scene scene(desc);
        scene.enable_profiling(profile);
        const BounceLayout layout = bounce_layout_for(integrator, bounce_layers);
        std::signal(SIGINT, on_interrupt);
        std::signal(SIGTERM, on_interrupt);
        for (const FrameToRender& this_frame : frames) {
            const std::string& output = this_frame.output;
            settings.seed = std::uint64_t(this_frame.seed);
            const Camera camera(desc.camera.at_time(this_frame.time), width, height);
            std::optional<Camera> previous;
            if (this_frame.number)
                previous.emplace(desc.camera.at_time(this_frame.time - 1 / fps), width, height);
            settings.previous_camera = previous ? &*previous : nullptr;
            const auto start = std::chrono::steady_clock::now();

            // One share of the frame's samples into a film of its own; `task` 0/1 for the whole.
            const bool whole = task_text.empty() && task_total == 0;
            // The header of a film holding `task`'s samples after `seconds` of rendering.
            auto output_info = [&](const Film& f, const RenderTask& task, double seconds) {
                OutputInfo info;
                info.spp = f.sample_counts();
                info.provenance.seed = this_frame.seed;
                info.provenance.range = task_samples(frame_spp, task);
                // Pixel p holds sample indices 0 .. n_p − 1: the range covers them all.
                if (settings.adaptive.enabled)
                    info.provenance.range->end = info.provenance.range->begin + info.spp.max;
                if (!whole) {
                    info.provenance.task_index = task.index;
                    info.provenance.task_count = task.count;
                }
                info.render_seconds = float(seconds);
                info.scene = scene_path;
                info.frame = this_frame.number;
                return info;
            };
            auto render_share = [&](const RenderTask& task,
                                    const IterationCallback& after_iteration,
                                    double& seconds_before) {
                const statmc::layers::SampleRange range = task_samples(frame_spp, task);
                RenderSettings share = settings;
                if (!whole)
                    share.schedule = schedule_for_spp(range.count());
                share.first_sample = std::uint64_t(range.begin);
                share.checkpoint_seconds = checkpoint_seconds;
                auto film = std::make_unique<Film>(width, height, layout);
                if (share.previous_camera)
                    film->track_motion();
                CheckpointIdentity identity{scene_path,      desc.source_crc,
                                            this_frame.seed, width,
                                            height,     task.index,
                                            task.count, range.begin,
                                            range.end,  settings_text(share, bounce_layers)};
                const std::string checkpoint = checkpoint_path(output);
                seconds_before = 0;
                if (resume && std::filesystem::exists(checkpoint)) {
                    const CheckpointProgress done = read_checkpoint(checkpoint, *film, identity);
                    share.samples_done = done.samples_done;
                    seconds_before = done.render_seconds;
                    std::fprintf(
                        stderr,
                        "%s: resuming from checkpoint %s: %llu of %d samples per pixel done\n",
                        output.c_str(), checkpoint.c_str(),
                        static_cast<unsigned long long>(done.samples_done), range.count());
                }
                CheckpointCallback save;
                if (checkpoint_seconds > 0)
                    save = [&, identity](const Film& f, std::uint64_t samples_done) {
                        const double seconds =
                            seconds_before +
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                                .count();
                        try {
                            write_checkpoint(checkpoint, f, identity, {samples_done, seconds});
                        } catch (const statmc::layers::FileError& e) {
                            // The render goes on; the previous checkpoint, if any, is intact.
                            std::fprintf(stderr,
                                         "statmc-render: warning: %s; the previous checkpoint is "
                                         "kept and the render continues\n",
                                         e.what());
                        }
                    };
                const RenderStats stats =
                    render(scene, camera, share, *film, &g_interrupted, after_iteration, save);
                const OutputInfo info = output_info(*film, task, seconds_before + stats.seconds);
                return std::make_tuple(std::move(film), stats, info);
            };
            auto write_denoised = [&](const OIIO::ImageBuf& image) {
                if (!denoise)
                    return;
                OIIO::ImageBuf denoised;
                const statmc::DenoiseImageOptions options;
                if (!statmc::denoise(denoised, image, options))
                    throw std::runtime_error("denoise: " + denoised.geterror());
                write_exr(denoised, denoised_path(output));
            };

            // SIGTERM is what schedulers send on preemption: it stops the render like Ctrl-C,
            // and what was rendered is written with its true counts (or, checkpointing, saved);
            // the handlers are installed above, before the first frame.
            RenderStats stats;
            Film::SampleCounts counts;
            if (task_total > 0) {
                // The tasks one after another, merged in task order as statmc --merge would.
                std::vector<OIIO::ImageBuf> parts;
                for (int t = 0; t < task_total && !g_interrupted.load(); ++t) {
                    double before = 0;
                    auto [film, task_stats, info] = render_share({t, task_total}, {}, before);
                    stats.samples += task_stats.samples;
                    stats.seconds += task_stats.seconds;
                    stats.tile_cycles += task_stats.tile_cycles;
                    if (task_stats.interrupted)
                        break;
                    parts.push_back(make_output_image(*film, info));
                }
                statmc::layers::install_write_signal_handlers();
                if (int(parts.size()) < task_total) {
                    std::fprintf(
                        stderr,
                        "statmc-render: interrupted after %zu of %d tasks; %s not written\n",
                        parts.size(), task_total, output.c_str());
                    return 130;
                }
                OIIO::ImageBuf merged = merge_tasks(parts);
                merged.specmod().attribute(statmc::layers::attr::kRenderTime, float(stats.seconds));
                merged.specmod().attribute(statmc::layers::attr::kScene, scene_path);
                write_exr(merged, output);
                write_denoised(merged);
                counts = Film::SampleCounts{frame_spp, frame_spp, double(frame_spp), true};
            } else {
                IterationCallback after_iteration;
                if (every_iteration)
                    after_iteration = [&](int, const Film& f, const IterationStats&) {
                        OutputInfo info = output_info(
                            f, task,
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                                .count());
                        // The samples so far, not the whole range.
                        info.provenance.range->end = info.provenance.range->begin + info.spp.min;
                        const OIIO::ImageBuf image = make_output_image(f, info);
                        write_exr(image, output);
                        write_denoised(image);
                    };
                double before = 0;
                auto [film, share_stats, info] = render_share(task, after_iteration, before);
                statmc::layers::install_write_signal_handlers();
                stats = share_stats;
                counts = info.spp;
                if (checkpoint_seconds > 0 && !stats.complete) {
                    // The film is saved; an output now would be a partial task that merges wrongly.
                    std::fprintf(
                        stderr,
                        "statmc-render: interrupted: %s holds the render so far; run again "
                        "with --resume to finish %s\n",
                        checkpoint_path(output).c_str(), output.c_str());
                    return 130;
                }
                const OIIO::ImageBuf image = make_output_image(*film, info);
                write_exr(image, output);
                write_denoised(image);
                if (stats.complete) {  // the output holds it all now
                    std::error_code ignored;
                    std::filesystem::remove(checkpoint_path(output), ignored);
                }
            }
            if (!quiet && settings.adaptive.enabled)
                std::fprintf(stderr,
                             "%s: %dx%d, adaptive: %.1f spp on average, %d to %d%s%s, %.2f s, "
                             "%.2f Msamples/s\n",
                             output.c_str(), width, height, counts.mean, counts.min, counts.max,
                             stats.converged ? ", every pixel within the noise threshold" : "",
                             stats.interrupted ? " (interrupted)" : "", stats.seconds,
                             stats.seconds > 0 ? double(stats.samples) / stats.seconds * 1e-6
                                               : 0.0);
            else if (!quiet)
                std::fprintf(stderr, "%s: %dx%d, %s%d spp%s, %.2f s, %.2f Msamples/s\n",
                             output.c_str(), width, height, counts.uniform ? "" : "at least ",
                             counts.min, stats.interrupted ? " (interrupted)" : "", stats.seconds,
                             stats.seconds > 0 ? double(stats.samples) / stats.seconds * 1e-6
                                               : 0.0);
            if (profile) {
                const auto t = scene.traversal_counters();
                std::printf("%s: %dx%d, %d spp, %zu triangles, threads %s\n", scene_path.c_str(),
                            width, height, counts.min, scene.triangle_count(),
                            threads > 0 ? std::to_string(threads).c_str() : "all");
                std::printf("  %.3f s, %.3f Msamples/s, %.2f Mrays/s, %.2f rays/sample\n",
                            stats.seconds, double(stats.samples) / stats.seconds * 1e-6,
                            double(t.rays) / stats.seconds * 1e-6,
                            stats.samples ? double(t.rays) / double(stats.samples) : 0.0);
                std::printf(
                    "  Embree traversal %.1f%% of render time, shading and the rest %.1f%%\n",
                    100.0 * double(t.cycles) / double(stats.tile_cycles),
                    100.0 - 100.0 * double(t.cycles) / double(stats.tile_cycles));
            }
            // A stop that came after the last sample changed nothing: the output is whole.
            if (stats.interrupted && !stats.complete)
                return 130;
        }
        return 0;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "statmc-render: error: out of memory rendering %s\n",
                     scene_path.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "statmc-render: error: %s\n", e.what());
        return 1;
    }
}
