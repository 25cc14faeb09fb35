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
#include <string>

#include <CLI/CLI.hpp>

#include "statmc/denoise/denoise.h"

#include "sampling_options.h"
#include "statmc/render/camera.h"
#include "statmc/render/exr_output.h"
#include "statmc/render/progress.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"

namespace {

std::atomic<bool> g_interrupted{false};

// SIGINT or SIGTERM. Async-signal-safe: sets a lock-free flag; a second signal gets the
// default action.
extern "C" void on_interrupt(int signal_number)
{
    g_interrupted.store(true);
    std::signal(signal_number, SIG_DFL);
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

// An integer option's range in words: CLI11's PositiveNumber and NonNegativeNumber print the
// largest double as their upper bound.
CLI::Validator integer_at_least(int minimum)
{
    return CLI::Validator(
        [minimum](std::string& text) -> std::string {
            int value = 0;
            const char* end = text.data() + text.size();
            const auto r = std::from_chars(text.data(), end, value);
            if (r.ec != std::errc() || r.ptr != end || value < minimum)
                return "must be an integer >= " + std::to_string(minimum) + ", got '" + text + "'";
            return {};
        },
        "INT>=" + std::to_string(minimum));
}

}  // namespace

int main(int argc, char** argv)
{
    using namespace statmc::render;
    CLI::App app{"statmc-render: path-trace a pbrt-v3 scene (Embree 3) into a statistics EXR\n"
                 "(mean, variance, Box-Cox moments, sample count, albedo/normal/depth guides)."};
    std::string scene_path, output;
    int spp = 0, iterations = 0, seed = 0, threads = 0, maxdepth = -1;
    std::string resolution;
    bool denoise = false, quiet = false, profile = false, every_iteration = false,
         bounce_layers = false;
    SamplingOptions sampling;
    app.add_option("scene", scene_path, "pbrt-v3 scene file")->required();
    app.add_option("-o,--output", output, "output statistics EXR")->required();
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
    app.add_flag(
        "--bounce-layers", bounce_layers,
        "track and write every per-bounce layer (L and win counts) even with classic RR and "
        "standard MIS [default: only those --rr/--mis use]");
    app.add_flag("--denoise", denoise,
                 "also write the denoised image to OUT.denoised.exr [default: off]");
    app.add_flag(
        "--write-every-iteration", every_iteration,
        "rewrite OUT (and OUT.denoised.exr with --denoise) after every progressive iteration, "
        "each time atomically, to watch the render refine [default: off]");
    app.add_flag("-q,--quiet", quiet, "no progress bar and no summary [default: off]");
    app.add_flag("--profile", profile,
                 "print samples/s, rays/s and the share of render time spent in Embree traversal "
                 "(the rest is shading, sampling and accumulation) [default: off]");
    CLI11_PARSE(app, argc, argv);

    try {
        {  // Fail before rendering, not after, when the output cannot be written.
            const std::filesystem::path out(output);
            const auto dir = out.has_parent_path() ? out.parent_path() : std::filesystem::path(".");
            if (!std::filesystem::is_directory(dir))
                throw std::runtime_error(output + ": cannot write: directory '" + dir.string() +
                                         "' does not exist");
        }
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
        sampling.apply(integrator);
        // Before anything is allocated: the same limits for --resolution and the Film.
        require_renderable_resolution(width, height, bounce_layout_for(integrator, bounce_layers),
                                      resolution.empty() ? desc.film_where : "--resolution");
        settings.progress = !quiet && Progress::stderr_is_terminal();

        Scene scene(desc);
        scene.enable_profiling(profile);
        const Camera camera(desc.camera, width, height);
        Film film(width, height, bounce_layout_for(integrator, bounce_layers));
        const auto start = std::chrono::steady_clock::now();
        auto write_outputs = [&](const Film& f, double seconds) {
            OutputInfo info;
            info.spp = f.sample_counts();
            info.seed = seed;
            info.render_seconds = float(seconds);
            info.scene = scene_path;
            const OIIO::ImageBuf image = make_output_image(f, info);
            write_exr(image, output);
            if (denoise) {
                OIIO::ImageBuf denoised;
                if (!statmc::denoise(denoised, image, statmc::DenoiseImageOptions{}))
                    throw std::runtime_error("denoise: " + denoised.geterror());
                write_exr(denoised, denoised_path(output));
            }
            return info;
        };
        IterationCallback after_iteration;
        if (every_iteration)
            after_iteration = [&](int, const Film& f, const IterationStats&) {
                write_outputs(
                    f, std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                           .count());
            };
        // SIGTERM is what schedulers send on preemption: it stops the render like Ctrl-C,
        // and what was rendered is written with its true counts.
        std::signal(SIGINT, on_interrupt);
        std::signal(SIGTERM, on_interrupt);
        const RenderStats stats =
            render(scene, camera, settings, film, &g_interrupted, after_iteration);
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
        const OutputInfo info = write_outputs(film, stats.seconds);
        if (!quiet)
            std::fprintf(stderr, "%s: %dx%d, %s%d spp%s, %.2f s, %.2f Msamples/s\n", output.c_str(),
                         width, height, info.spp.uniform ? "" : "at least ", info.spp.min,
                         stats.interrupted ? " (interrupted)" : "", stats.seconds,
                         stats.seconds > 0 ? double(stats.samples) / stats.seconds * 1e-6 : 0.0);
        if (profile) {
            const auto t = scene.traversal_counters();
            std::printf("%s: %dx%d, %d spp, %zu triangles, threads %s\n", scene_path.c_str(), width,
                        height, info.spp.min, scene.triangle_count(),
                        threads > 0 ? std::to_string(threads).c_str() : "all");
            std::printf("  %.3f s, %.3f Msamples/s, %.2f Mrays/s, %.2f rays/sample\n",
                        stats.seconds, double(stats.samples) / stats.seconds * 1e-6,
                        double(t.rays) / stats.seconds * 1e-6,
                        stats.samples ? double(t.rays) / double(stats.samples) : 0.0);
            std::printf("  Embree traversal %.1f%% of render time, shading and the rest %.1f%%\n",
                        100.0 * double(t.cycles) / double(stats.tile_cycles),
                        100.0 - 100.0 * double(t.cycles) / double(stats.tile_cycles));
        }
        return stats.interrupted ? 130 : 0;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "statmc-render: error: out of memory rendering %s\n",
                     scene_path.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "statmc-render: error: %s\n", e.what());
        return 1;
    }
}
