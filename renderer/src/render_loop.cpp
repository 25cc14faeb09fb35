#include "statmc/render/render_loop.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <stdexcept>

#include <pmmintrin.h>
#include <x86intrin.h>
#include <xmmintrin.h>

#include <tbb/parallel_for.h>

#include "statmc/core/thread_limit.h"

#include "statmc/render/progress.h"

namespace statmc::render {

std::vector<int> schedule_for_spp(int total_spp)
{
    std::vector<int> s;
    int done = 0, next = 4;
    while (done < total_spp) {
        const int n = std::min(next, total_spp - done);
        s.push_back(n);
        done += n;
        if (s.size() > 1)
            next *= 2;
    }
    return s;
}

std::vector<int> schedule_for_iterations(int iterations)
{
    std::vector<int> s;
    int next = 4;
    for (int i = 0; i < iterations; ++i) {
        s.push_back(next);
        if (i > 0)
            next *= 2;
    }
    return s;
}

BounceLayout bounce_layout_for(const IntegratorSettings& settings, bool record_all)
{
    BounceLayout layout;
    if (record_all || settings.roulette.mode == RouletteMode::Acrr)
        layout.luminance_bounces = settings.roulette.tracked_bounces + 1;
    if (record_all || settings.mis.mode == MisMode::Selective)
        layout.mis_bounces = settings.mis.tracked_bounces;
    return layout;
}

namespace {

// The render on whatever threads the calling arena has.
RenderStats render_in_arena(const Scene& scene, const Camera& camera,
                            const RenderSettings& settings, Film& film,
                            const std::atomic<bool>* cancel,
                            const IterationCallback& after_iteration)
{
    const auto start = std::chrono::steady_clock::now();
    const PathIntegrator integrator(scene, settings.integrator);
    constexpr int kTile = 16;
    const int tiles_x = (settings.width + kTile - 1) / kTile,
              tiles_y = (settings.height + kTile - 1) / kTile;
    const std::size_t npix = std::size_t(settings.width) * settings.height;

    std::uint64_t total = 0;
    for (int n : settings.schedule)
        total += std::uint64_t(n) * npix;
    Progress progress(total, settings.progress);

    const BounceLayout needed = bounce_layout_for(settings.integrator);
    if (!needed.empty() &&
        (!film.bounces || film.bounces->layout().luminance_bounces < needed.luminance_bounces ||
         film.bounces->layout().mis_bounces < needed.mis_bounces))
        throw std::invalid_argument("render: the film does not track the bounces ACRR/SMIS need");
    // Estimates steer sampling only from the second iteration on (§7, §8).
    std::optional<BounceEstimates> estimates;

    RenderStats rs;
    std::uint64_t first_sample = 0;
    for (std::size_t it = 0; it < settings.schedule.size(); ++it) {
        const int spp = settings.schedule[it];
        const bool may_stop = it > 0;
        IterationStats is{spp, 0};
        // Denoised here rather than after the previous iteration, so a render that stops
        // never pays for estimates no iteration will use.
        if (!needed.empty() && it > 0) {
            const auto denoise_start = std::chrono::steady_clock::now();
            // Without the albedo/normal guides: the estimates only steer sampling, and the
            // guided kernel costs about 4× (README, Performance); on Veach Ajar the
            // unguided estimates were as good (relative variance 86.9 vs 88.4) and ACRR's
            // cost 15% lower.
            estimates = film.bounces->denoise({}, settings.bounce_filter, settings.threads);
            is.denoise_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - denoise_start)
                    .count();
            if (cancel &&
                cancel->load()) {  // stopped while denoising: as if after the last iteration
                rs.interrupted = true;
                break;
            }
        }
        std::atomic<std::uint64_t> samples{0}, cycles{0};
        tbb::parallel_for(0, tiles_x * tiles_y, [&](int tile) {
            if (may_stop && cancel && cancel->load())
                return;
            const std::uint64_t t0 = __rdtsc();
            // Denormals flushed on every worker, so no pixel depends on the thread it ran on.
            _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
            _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
            const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
            const int x1 = std::min(x0 + kTile, settings.width),
                      y1 = std::min(y0 + kTile, settings.height);
            PathRecord record;
            std::vector<float> bounce_values(
                film.bounces ? std::size_t(film.bounces->layout().quantities()) : 0);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const std::size_t pixel = std::size_t(y) * settings.width + x;
                    // PixelEstimates{} steers nothing, as no estimates would.
                    const PixelEstimates pixel_estimates =
                        estimates ? estimates->pixel(pixel) : PixelEstimates{};
                    for (int s = 0; s < spp; ++s) {
                        Sampler sampler(settings.seed, pixel, first_sample + std::uint64_t(s));
                        const float jx = sampler.get1d(), jy = sampler.get1d();
                        const Ray ray = camera.generate(float(x) + jx, float(y) + jy);
                        GuideSample guide;
                        const Rgb L =
                            integrator.radiance(ray, sampler, guide,
                                                film.bounces ? &record : nullptr, &pixel_estimates);
                        const float value[3] = {L.r, L.g, L.b};
                        film.stats.add(x, y, value, jx, jy);
                        if (film.bounces) {
                            bounce_sample(record, film.bounces->layout(), bounce_values.data());
                            film.bounces->add(x, y, bounce_values.data());
                        }
                        for (int c = 0; c < 3; ++c) {
                            film.albedo_sum[c * npix + pixel] += guide.albedo[c];
                            film.normal_sum[c * npix + pixel] += guide.normal[c];
                        }
                        film.depth_sum[pixel] += guide.depth;
                    }
                }
            const std::uint64_t n = std::uint64_t(x1 - x0) * (y1 - y0) * spp;
            samples += n;
            cycles += __rdtsc() - t0;
            progress.advance(n);
        });
        rs.samples += samples.load();
        rs.tile_cycles += cycles.load();
        first_sample += std::uint64_t(spp);
        const bool stopped = cancel && cancel->load() && may_stop;
        if (stopped && samples.load() < std::uint64_t(spp) * npix) {
            rs.interrupted = true;
            ++rs.iterations_done;  // partial
            break;
        }
        ++rs.iterations_done;
        if (after_iteration)
            after_iteration(int(it), film, is);
        if (cancel && cancel->load()) {
            rs.interrupted = true;
            break;
        }
    }
    progress.finish();
    rs.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return rs;
}

}  // namespace

RenderStats render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                   Film& film, const std::atomic<bool>* cancel,
                   const IterationCallback& after_iteration)
{
    // An arena, not tbb::global_control: the limit holds for this render only, never for
    // the rest of the process (a host may render and denoise side by side).
    RenderStats stats;
    run_with_threads(settings.threads, [&] {
        stats = render_in_arena(scene, camera, settings, film, cancel, after_iteration);
    });
    return stats;
}

}  // namespace statmc::render
