// bench_sampling: the sampling-efficiency measurements of the seed's C.2 (Rath et al.
// 2022) for statmc-render's roulette and MIS choices. For each progressive iteration of
// each independent run it appends one CSV row:
//   cost      = process CPU time of the iteration (rendering + denoising the per-bounce
//               estimates, all threads) per camera sample. CPU time, not wall time: on a
//               machine shared with other jobs wall time measures their load as much as
//               ours. Wall time (seconds, elapsed) and the denoising share are given too,
//   rel_var   = relative variance of one sample: the iteration's own samples give an
//               image I_k (from the accumulated means), and
//               rel_var = spp_k · mean over pixels and channels of (I_k − ref)² / (ref² + 0.01)
//               (Rousselle et al. 2011's relMSE with its ε, times the samples averaged),
//   efficiency = 1 / (cost · rel_var),
// and the relMSE of the accumulated image against the reference with the elapsed time,
// for error-versus-time plots, also without its 0.1% largest pixel-channel errors
// (relmse_trimmed: a firefly or two would otherwise decide a short run's error). The reference is
// an EXR rendered by statmc-render itself. Time spent computing these metrics is excluded.
// scripts/sampling_bench.sh drives it.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "statmc/layers/exr_files.h"

#include "sampling_options.h"
#include "statmc/render/camera.h"
#include "statmc/render/render_loop.h"
#include "statmc/render/scene.h"
#include "statmc/render/scene_parser.h"

using namespace statmc::render;

namespace {

struct Reference {
    int width = 0, height = 0;
    std::vector<double> rgb;  // channel-major
};

Reference read_reference(const std::string& path)
{
    const OIIO::ImageBuf buf = statmc::layers::read_image_file(path);
    Reference ref{buf.spec().width, buf.spec().height, {}};
    const std::size_t n = std::size_t(ref.width) * ref.height;
    ref.rgb.resize(3 * n);
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const int ch = buf.spec().channelindex(names[c]);
        if (ch < 0)
            throw std::runtime_error(path + ": no channel " + names[c]);
        for (int y = 0; y < ref.height; ++y)
            for (int x = 0; x < ref.width; ++x)
                ref.rgb[c * n + std::size_t(y) * ref.width + x] = buf.getchannel(x, y, 0, ch);
    }
    return ref;
}

// CPU time of this process, all threads.
double cpu_seconds()
{
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

constexpr double kEpsilon = 0.01;  // Rousselle et al.'s relMSE denominator offset

double rel_error(double value, double truth)
{
    return (value - truth) * (value - truth) / (truth * truth + kEpsilon);
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{
        "bench_sampling: per-iteration cost, relative variance and efficiency of statmc-render's "
        "sampling (seed C.2), appended to a CSV"};
    std::string scene_path, reference_path, csv_path, label, breakdown_path;
    int width = 0, height = 0, iterations = 16, spp = 4, runs = 4, seed = 1, threads = 0,
        progressive = 0;
    double budget = 0;
    SamplingOptions sampling;
    app.add_option("scene", scene_path, "pbrt-v3 scene")->required();
    app.add_option("--reference", reference_path, "high-spp EXR of the same scene and size")
        ->required();
    app.add_option("--csv", csv_path, "CSV to append to (header written when new)")->required();
    app.add_option("--label", label, "configuration name in the CSV")->required();
    app.add_option("--iterations", iterations, "iterations per run")->capture_default_str();
    app.add_option("--spp-per-iteration", spp, "samples per pixel of each iteration")
        ->capture_default_str();
    app.add_option(
        "--progressive-spp", progressive,
        "instead of --iterations x --spp-per-iteration: the progressive schedule 4, 4, 8, ... "
        "to this many spp (docs/method.md §6)");
    app.add_option("--runs", runs, "independent runs (seeds seed, seed+1, ...)")
        ->capture_default_str();
    app.add_option("--seed", seed, "first seed")->capture_default_str();
    app.add_option("--threads", threads, "worker threads, 0 = all")->capture_default_str();
    app.add_option("--time-budget", budget,
                   "stop a run after the iteration that reaches this many CPU "
                   "seconds (0 = run all iterations)")
        ->capture_default_str();
    app.add_option("--breakdown", breakdown_path,
                   "CSV to append one row per run to: where the render's time went (Embree "
                   "closest-hit and shadow-ray queries, per-bounce statistics, the rest of the "
                   "tiles' time, denoising the estimates), from time stamp counters");
    add_sampling_options(app, sampling);
    CLI11_PARSE(app, argc, argv);

    try {
        const Reference ref = read_reference(reference_path);
        width = ref.width;
        height = ref.height;
        const SceneDescription desc = parse_scene_file(scene_path);
        Scene scene(desc);  // built once: BVH construction is not part of the cost
        scene.enable_profiling(!breakdown_path.empty());
        const Camera camera(desc.camera, width, height);
        RenderSettings rs;
        rs.width = width;
        rs.height = height;
        if (progressive > 0)
            rs.schedule = schedule_for_spp(progressive);
        else
            rs.schedule.assign(std::size_t(iterations), spp);
        rs.threads = threads;
        rs.integrator.maxdepth = desc.maxdepth;
        sampling.apply(rs);
        const std::size_t npix = std::size_t(width) * height;

        const bool fresh =
            !std::filesystem::exists(csv_path) || std::filesystem::file_size(csv_path) == 0;
        std::FILE* csv = std::fopen(csv_path.c_str(), "a");
        if (!csv)
            throw std::runtime_error(csv_path + ": cannot open");
        if (fresh)
            std::fprintf(csv, "label,run,iteration,spp,total_spp,seconds,cpu_seconds,denoise_"
                              "seconds,elapsed,cpu_elapsed,cost,rel_var,"
                              "efficiency,relmse,relmse_trimmed\n");

        std::FILE* breakdown = nullptr;
        if (!breakdown_path.empty()) {
            const bool new_file = !std::filesystem::exists(breakdown_path) ||
                                  std::filesystem::file_size(breakdown_path) == 0;
            breakdown = std::fopen(breakdown_path.c_str(), "a");
            if (!breakdown)
                throw std::runtime_error(breakdown_path + ": cannot open");
            if (new_file)
                std::fprintf(breakdown,
                             "label,run,samples,rays,shadow_rays,tile_cycles,trace_cycles,"
                             "shadow_cycles,bounce_cycles,denoise_seconds,seconds\n");
        }

        for (int run = 0; run < runs; ++run) {
            rs.seed = std::uint64_t(seed + run);
            Film film(width, height, bounce_layout_for(rs.integrator));
            std::vector<double> previous(3 * npix,
                                         0.0);  // accumulated means after the last iteration
            std::vector<double> errors;
            double previous_n = 0, elapsed = 0, cpu_elapsed = 0;
            std::atomic<bool> stop{false};
            double denoise_total = 0;
            const Scene::TraversalCounters before = scene.traversal_counters();
            auto t0 = std::chrono::steady_clock::now();
            double cpu0 = cpu_seconds();
            auto measure = [&](int it, const Film& f, const IterationStats& is) {
                const int k_spp = is.spp;  // this iteration's samples per pixel
                denoise_total += is.denoise_seconds;
                const double seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                const double cpu = cpu_seconds() - cpu0;
                elapsed += seconds;
                cpu_elapsed += cpu;
                const double n_now = previous_n + k_spp;
                double iteration_error = 0, accumulated_error = 0;
                errors.clear();
                for (int y = 0; y < height; ++y)
                    for (int x = 0; x < width; ++x) {
                        const std::size_t i = std::size_t(y) * width + x;
                        const auto& px = f.stats.at(x, y);
                        for (int c = 0; c < 3; ++c) {
                            const double mean = px.raw[c].mean, truth = ref.rgb[c * npix + i];
                            // This iteration's samples alone, from the running means.
                            const double own =
                                (mean * n_now - previous[c * npix + i] * previous_n) / k_spp;
                            iteration_error += rel_error(own, truth);
                            accumulated_error += rel_error(mean, truth);
                            errors.push_back(rel_error(mean, truth));
                            previous[c * npix + i] = mean;
                        }
                    }
                previous_n = n_now;
                // Trimmed: the largest 0.1% of errors dropped.
                const std::size_t keep = errors.size() - errors.size() / 1000;
                std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(keep - 1),
                                 errors.end());
                const double trimmed =
                    std::accumulate(errors.begin(), errors.begin() + std::ptrdiff_t(keep), 0.0) /
                    double(keep);
                const double samples = double(is.samples);
                const double cost = cpu / samples;
                const double rel_var = k_spp * iteration_error / double(3 * npix);
                std::fprintf(csv,
                             "%s,%d,%d,%d,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%.6e,%.6e,%.6e,%.6e,%.6e\n",
                             label.c_str(), run, it, k_spp, int(n_now), seconds, cpu,
                             is.denoise_seconds, elapsed, cpu_elapsed, cost, rel_var,
                             1.0 / (cost * rel_var), accumulated_error / double(3 * npix), trimmed);
                if (budget > 0 && cpu_elapsed >= budget)
                    stop = true;
                t0 = std::chrono::steady_clock::now();  // metrics excluded
                cpu0 = cpu_seconds();
            };
            const RenderStats stats = render(scene, camera, rs, film, &stop, measure);
            if (breakdown) {
                const Scene::TraversalCounters after = scene.traversal_counters();
                const std::uint64_t shadow = after.shadow_cycles - before.shadow_cycles;
                std::fprintf(breakdown, "%s,%d,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%.6f,%.6f\n",
                             label.c_str(), run, (unsigned long long)stats.samples,
                             (unsigned long long)(after.rays - before.rays),
                             (unsigned long long)(after.shadow_rays - before.shadow_rays),
                             (unsigned long long)stats.tile_cycles,
                             (unsigned long long)(after.cycles - before.cycles - shadow),
                             (unsigned long long)shadow, (unsigned long long)stats.bounce_cycles,
                             denoise_total, stats.seconds);
            }
            std::fprintf(stderr, "%s run %d: %.0f spp in %.2f s (%.2f CPU s)\n", label.c_str(), run,
                         previous_n, elapsed, cpu_elapsed);
        }
        std::fclose(csv);
        if (breakdown)
            std::fclose(breakdown);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_sampling: error: %s\n", e.what());
        return 1;
    }
}
