#include "statmc/render/render_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
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

std::uint64_t schedule_samples(const std::vector<int>& schedule)
{
    std::uint64_t total = 0;
    for (int n : schedule)
        total += std::uint64_t(n);
    return total;
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

// One sample's motion to the previous frame: where the previous camera saw the sample's
// first hit (a miss: a point far along the ray, i.e. the direction), minus where the sample
// is now. A point behind the previous camera has no defined motion and adds 0.
void add_motion(Film& film, std::size_t pixel, std::size_t npix, const Camera& previous,
                const Ray& ray, const GuideSample& guide, float x, float y)
{
    const Vec3 p = guide.hit ? guide.first_hit : ray.origin + ray.direction * 1e7f;
    float px = 0, py = 0;
    if (!previous.raster(p, px, py))
        return;
    film.motion_sum[pixel] += double(px) - x;
    film.motion_sum[npix + pixel] += double(py) - y;
}

// Flush-to-zero and denormals-are-zero for the scope's lifetime; the caller's mode after.
class FlushDenormals {
public:
    FlushDenormals() : saved_(_mm_getcsr())
    {
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    }
    ~FlushDenormals() { _mm_setcsr(saved_); }
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

private:
    unsigned int saved_;
};

// How many samples per pixel the next pass takes when the render checkpoints: about a
// quarter of the checkpoint interval, and at most 5 s (a scheduler's SIGTERM is followed by
// SIGKILL after its grace period, 30 s in Slurm by default), at the rate measured so far;
// one sample per pixel before anything is measured.
int pass_samples(double checkpoint_seconds, double samples_per_second, std::size_t npix,
                 std::uint64_t remaining)
{
    double spp = 1;
    if (samples_per_second > 0)
        spp = std::floor(std::min(0.25 * checkpoint_seconds, 5.0) * samples_per_second /
                         double(npix));
    return int(std::clamp(spp, 1.0, double(std::min<std::uint64_t>(remaining, 1 << 20))));
}

// The render on whatever threads the calling arena has.
RenderStats render_in_arena(const Scene& scene, const Camera& camera,
                            const RenderSettings& settings, Film& film,
                            const std::atomic<bool>* cancel,
                            const IterationCallback& after_iteration,
                            const CheckpointCallback& checkpoint)
{
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const PathIntegrator integrator(scene, settings.integrator);
    constexpr int kTile = 16;
    const int tiles_x = (settings.width + kTile - 1) / kTile,
              tiles_y = (settings.height + kTile - 1) / kTile;
    const std::size_t npix = std::size_t(settings.width) * settings.height;

    const std::uint64_t schedule_total = schedule_samples(settings.schedule);
    if (settings.samples_done > schedule_total)
        throw std::invalid_argument(
            "render: the film already holds more samples than the schedule");
    Progress progress((schedule_total - settings.samples_done) * npix, settings.progress);

    const BounceLayout needed = bounce_layout_for(settings.integrator);
    const bool tracks_bounces = !needed.empty();
    const AdaptiveSettings& adaptive = settings.adaptive;
    if (adaptive.enabled) {
        if (const std::string problem = adaptive.validate(); !problem.empty())
            throw std::invalid_argument("render: adaptive sampling: " + problem);
        if (settings.first_sample != 0)
            throw std::invalid_argument(
                "render: adaptive sampling decides every pixel's count from the whole frame, "
                "so it renders whole frames, not a farm task's share of the samples");
    }
    // Steered iterations take their decisions from the film at their start.
    const bool steered = tracks_bounces || adaptive.enabled;
    if (tracks_bounces &&
        (!film.bounces || film.bounces->layout().luminance_bounces < needed.luminance_bounces ||
         film.bounces->layout().mis_bounces < needed.mis_bounces))
        throw std::invalid_argument("render: the film does not track the bounces ACRR/SMIS need");
    // Passes within an iteration only without steering: the estimates of a steered
    // iteration come from the film at its start, which a checkpoint inside it would not hold.
    const bool in_passes = settings.checkpoint_seconds > 0;
    // Estimates steer sampling only from the second iteration on (§7, §8).
    std::optional<BounceEstimates> estimates;
    const bool profiling = scene.profiling();
    RenderStats rs;

    // Samples [first, first + spp) of every pixel, tile by tile; with `counts` (adaptive
    // sampling), pixel p's next counts[p] samples instead, its stream carrying on from the
    // samples it holds. A skippable pass leaves out the tiles not yet started once `cancel`
    // is set. Returns the samples taken.
    auto render_pass = [&](std::uint64_t first, int spp, const std::vector<std::uint32_t>* counts,
                           bool skippable) {
        std::atomic<std::uint64_t> samples{0}, cycles{0}, bounce_cycles{0};
        tbb::parallel_for(0, tiles_x * tiles_y, [&](int tile) {
            if (skippable && cancel && cancel->load())
                return;
            const std::uint64_t t0 = __rdtsc();
            // Denormals flushed on every worker, so no pixel depends on the thread it ran on;
            // and only here, so that what runs after the render (the output, a merge, the
            // estimates' filter) never depends on which threads rendered tiles.
            const FlushDenormals flush;
            const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
            const int x1 = std::min(x0 + kTile, settings.width),
                      y1 = std::min(y0 + kTile, settings.height);
            PathRecord record;
            std::vector<float> bounce_values(
                film.bounces ? std::size_t(film.bounces->layout().quantities()) : 0);
            std::uint64_t n = 0, bounce_cycles_local = 0;
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const std::size_t pixel = std::size_t(y) * settings.width + x;
                    // PixelEstimates{} steers nothing, as no estimates would.
                    const PixelEstimates pixel_estimates =
                        estimates ? estimates->pixel(pixel) : PixelEstimates{};
                    const int take = counts ? int((*counts)[pixel]) : spp;
                    const std::uint64_t begin =
                        counts ? std::uint64_t(film.stats.at(x, y).n) : first;
                    n += std::uint64_t(take);
                    for (int s = 0; s < take; ++s) {
                        Sampler sampler(settings.seed, pixel,
                                        settings.first_sample + begin + std::uint64_t(s));
                        const float jx = sampler.get1d(), jy = sampler.get1d();
                        const Ray ray = camera.generate(float(x) + jx, float(y) + jy);
                        GuideSample guide;
                        const Rgb L =
                            integrator.radiance(ray, sampler, guide,
                                                film.bounces ? &record : nullptr, &pixel_estimates);
                        const float value[3] = {L.r, L.g, L.b};
                        film.stats.add(x, y, value);
                        if (film.bounces) {
                            const std::uint64_t b0 = profiling ? __rdtsc() : 0;
                            bounce_sample(record, film.bounces->layout(), bounce_values.data());
                            film.bounces->add(x, y, bounce_values.data());
                            if (profiling)
                                bounce_cycles_local += __rdtsc() - b0;
                        }
                        double albedo_square = 0, normal_square = 0;
                        for (int c = 0; c < 3; ++c) {
                            film.albedo_sum[c * npix + pixel] += guide.albedo[c];
                            film.normal_sum[c * npix + pixel] += guide.normal[c];
                            albedo_square += double(guide.albedo[c]) * guide.albedo[c];
                            normal_square += double(guide.normal[c]) * guide.normal[c];
                        }
                        film.albedo_squares[pixel] += albedo_square;
                        film.normal_squares[pixel] += normal_square;
                        film.depth_sum[pixel] += guide.depth;
                        if (!film.motion_sum.empty())
                            add_motion(film, pixel, npix, *settings.previous_camera, ray, guide,
                                       float(x) + jx, float(y) + jy);
                    }
                }
            samples += n;
            cycles += __rdtsc() - t0;
            bounce_cycles += bounce_cycles_local;
            progress.advance(n);
        });
        rs.tile_cycles += cycles.load();
        rs.bounce_cycles += bounce_cycles.load();
        return samples.load();
    };

    auto last_checkpoint = Clock::now();
    std::uint64_t checkpointed = settings.samples_done, iteration_begin = 0;
    double samples_per_second = 0;
    auto save = [&](std::uint64_t done) {
        if (checkpoint && done > checkpointed) {
            checkpoint(film, done);
            checkpointed = done;
        }
        last_checkpoint = Clock::now();
    };
    for (std::size_t it = 0; it < settings.schedule.size(); ++it) {
        const int spp = settings.schedule[it];
        const std::uint64_t iteration_end = iteration_begin + std::uint64_t(spp);
        if (iteration_end <= settings.samples_done) {  // in the film already
            iteration_begin = iteration_end;
            ++rs.iterations_done;
            continue;
        }
        if (steered && settings.samples_done > iteration_begin)
            throw std::invalid_argument(
                "render: ACRR/SMIS and adaptive sampling resume only at an iteration boundary "
                "(their checkpoints are written there)");
        const bool may_stop = it > 0;
        IterationStats is{spp, 0};
        // Denoised here rather than after the previous iteration, so a render that stops
        // never pays for estimates no iteration will use.
        if (tracks_bounces && it > 0) {
            const auto denoise_start = Clock::now();
            // Without the albedo/normal guides: the estimates only steer sampling, and the
            // guided kernel costs about 4× (README, Performance); on Veach Ajar the
            // unguided estimates were as good (relative variance 86.9 vs 88.4) and ACRR's
            // cost 15% lower.
            estimates = film.bounces->denoise({}, settings.bounce_filter, settings.threads);
            is.denoise_seconds =
                std::chrono::duration<double>(Clock::now() - denoise_start).count();
            if (cancel &&
                cancel->load()) {  // stopped while denoising: as if after the last iteration
                save(iteration_begin);
                rs.interrupted = true;
                break;
            }
        }
        std::optional<SampleAllocation> allocation;
        if (adaptive.enabled && iteration_begin >= std::uint64_t(adaptive.min_spp)) {
            const auto start_map = Clock::now();
            allocation =
                allocate_samples(relative_variance(film.stats, adaptive.filter, settings.threads),
                                 film.stats, spp, adaptive);
            is.denoise_seconds += std::chrono::duration<double>(Clock::now() - start_map).count();
            if (allocation->total == 0) {  // every pixel met the noise threshold
                rs.converged = true;
                break;
            }
        }
        std::uint64_t next = std::max(iteration_begin, settings.samples_done);
        bool stopped = false;
        while (next < iteration_end) {
            const int pass = in_passes && !steered
                                 ? pass_samples(settings.checkpoint_seconds, samples_per_second,
                                                npix, iteration_end - next)
                                 : int(iteration_end - next);
            const auto pass_start = Clock::now();
            // A checkpointing render stops only at pass boundaries, with whole passes.
            const std::uint64_t taken = render_pass(
                next, pass, allocation ? &allocation->counts : nullptr, may_stop && !in_passes);
            rs.samples += taken;
            is.samples += taken;
            const double seconds = std::chrono::duration<double>(Clock::now() - pass_start).count();
            if (seconds > 0)
                samples_per_second = double(taken) / seconds;
            const std::uint64_t expected =
                allocation ? allocation->total : std::uint64_t(pass) * npix;
            if (taken < expected) {  // tiles skipped: a partial iteration
                rs.interrupted = true;
                ++rs.iterations_done;
                stopped = true;
                break;
            }
            next += std::uint64_t(pass);
            // A stop on the last pass finds the render complete: it is written, not saved.
            if (in_passes && cancel && cancel->load() && next < schedule_total) {
                save(next);
                rs.interrupted = true;
                stopped = true;
                break;
            }
            if (in_passes && next < schedule_total &&
                std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >=
                    settings.checkpoint_seconds)
                save(next);
        }
        if (stopped)
            break;
        iteration_begin = iteration_end;
        ++rs.iterations_done;
        if (after_iteration)
            after_iteration(int(it), film, is);
        if (cancel && cancel->load()) {
            if (in_passes && iteration_end < schedule_total)
                save(iteration_end);
            rs.interrupted = true;
            break;
        }
    }
    rs.complete = iteration_begin == schedule_total || rs.converged;
    progress.finish();
    rs.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return rs;
}

}  // namespace

RenderStats render(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                   Film& film, const std::atomic<bool>* cancel,
                   const IterationCallback& after_iteration, const CheckpointCallback& checkpoint)
{
    if (!film.motion_sum.empty() && !settings.previous_camera)
        throw std::invalid_argument("render: a film that tracks motion needs the previous camera");
    // An arena, not tbb::global_control: the limit holds for this render only, never for
    // the rest of the process (a host may render and denoise side by side).
    RenderStats stats;
    run_with_threads(settings.threads, [&] {
        stats = render_in_arena(scene, camera, settings, film, cancel, after_iteration, checkpoint);
    });
    return stats;
}

}  // namespace statmc::render
