#include "statmc/render/render_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "statmc/core/thread_limit.h"
#include "statmc/render/progress.h"
#include "tile_pass.h"

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

BounceLayout bounce_layers_for(const IntegratorSettings& settings, bool bounce_layers)
{
    return bounce_layers ? bounce_layout_for(settings, true) : BounceLayout{};
}

namespace {

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

// A render's iterations: each steered by the film at its start (the bounce estimates of
// ACRR/SMIS, adaptive sampling's allocation), then rendered in passes: one pass per
// iteration, or, checkpointing, passes sized to the checkpoint interval with a checkpoint
// between them. Runs on whatever threads the calling arena has.
class RenderLoop {
public:
    using Clock = std::chrono::steady_clock;

    RenderLoop(const Scene& scene, const Camera& camera, const RenderSettings& settings, Film& film,
               const std::atomic<bool>* cancel, const IterationCallback& after_iteration,
               const CheckpointCallback& checkpoint)
        : settings_(settings), film_(film), cancel_(cancel), after_iteration_(after_iteration),
          checkpoint_(checkpoint), integrator_(scene, settings.integrator),
          npix_(std::size_t(settings.width) * settings.height),
          schedule_total_(schedule_samples(settings.schedule)),
          tracks_bounces_(!bounce_layout_for(settings.integrator).empty()),
          // Steered iterations take their decisions from the film at their start.
          steered_(tracks_bounces_ || settings.adaptive.enabled),
          // Passes within an iteration only without steering: the estimates of a steered
          // iteration come from the film at its start, which a checkpoint inside it would
          // not hold.
          in_passes_(settings.checkpoint_seconds > 0),
          progress_(checked_remaining() * npix_, settings.progress),
          pass_{integrator_, camera, settings, film, nullptr, progress_, scene.profiling()},
          checkpointed_(settings.samples_done)
    {
        require_steerable();
    }

    RenderStats run()
    {
        std::uint64_t iteration_begin = 0;
        for (std::size_t it = 0; it < settings_.schedule.size(); ++it) {
            const int spp = settings_.schedule[it];
            const std::uint64_t iteration_end = iteration_begin + std::uint64_t(spp);
            if (iteration_end <= settings_.samples_done) {  // in the film already
                iteration_begin = iteration_end;
                ++rs_.iterations_done;
                continue;
            }
            if (steered_ && settings_.samples_done > iteration_begin)
                throw std::invalid_argument(
                    "render: ACRR/SMIS and adaptive sampling resume only at an iteration "
                    "boundary (their checkpoints are written there)");
            IterationStats is{spp, 0};
            std::optional<SampleAllocation> allocation;
            if (!steer(it, iteration_begin, spp, is, allocation))
                break;
            if (!render_passes(iteration_begin, iteration_end, it > 0, allocation, is))
                break;
            iteration_begin = iteration_end;
            ++rs_.iterations_done;
            if (after_iteration_)
                after_iteration_(int(it), film_, is);
            if (cancel_ && cancel_->load()) {
                if (in_passes_ && iteration_end < schedule_total_)
                    save(iteration_end);
                rs_.interrupted = true;
                break;
            }
        }
        rs_.complete = iteration_begin == schedule_total_ || rs_.converged;
        progress_.finish();
        rs_.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
        return rs_;
    }

private:
    std::uint64_t checked_remaining() const
    {
        if (settings_.samples_done > schedule_total_)
            throw std::invalid_argument(
                "render: the film already holds more samples than the schedule");
        return schedule_total_ - settings_.samples_done;
    }

    void require_steerable() const
    {
        const AdaptiveSettings& adaptive = settings_.adaptive;
        if (adaptive.enabled) {
            if (const std::string problem = adaptive.validate(); !problem.empty())
                throw std::invalid_argument("render: adaptive sampling: " + problem);
            if (settings_.first_sample != 0)
                throw std::invalid_argument(
                    "render: adaptive sampling decides every pixel's count from the whole "
                    "frame, so it renders whole frames, not a farm task's share of the samples");
        }
        const BounceLayout needed = bounce_layout_for(settings_.integrator);
        if (tracks_bounces_ &&
            (!film_.steering ||
             film_.steering->layout().luminance_bounces < needed.luminance_bounces ||
             film_.steering->layout().mis_bounces < needed.mis_bounces))
            throw std::invalid_argument(
                "render: the film does not track the bounces ACRR/SMIS need");
    }

    // The steering of iteration `it` from the film at its start: the bounce estimates
    // (from the second iteration on, §7, §8) and adaptive sampling's allocation. False when
    // the render ends here: stopped while denoising, or every pixel converged.
    bool steer(std::size_t it, std::uint64_t iteration_begin, int spp, IterationStats& is,
               std::optional<SampleAllocation>& allocation)
    {
        // Denoised here rather than after the previous iteration, so a render that stops
        // never pays for estimates no iteration will use.
        if (tracks_bounces_ && it > 0) {
            const auto denoise_start = Clock::now();
            // Without the albedo/normal guides: the estimates only steer sampling, and the
            // guided kernel costs about 4× (docs/performance.md); on Veach Ajar the
            // unguided estimates were as good (relative variance 86.9 vs 88.4) and ACRR's
            // cost 15% lower.
            estimates_ = film_.steering->denoise(settings_.bounce_filter, settings_.threads);
            pass_.estimates = &*estimates_;
            is.denoise_seconds =
                std::chrono::duration<double>(Clock::now() - denoise_start).count();
            if (cancel_ && cancel_->load()) {  // stopped while denoising: as if after the last
                save(iteration_begin);         // iteration
                rs_.interrupted = true;
                return false;
            }
        }
        const AdaptiveSettings& adaptive = settings_.adaptive;
        if (adaptive.enabled && iteration_begin >= std::uint64_t(adaptive.min_spp)) {
            const auto start_map = Clock::now();
            allocation =
                allocate_samples(relative_variance(film_.stats, adaptive.filter, settings_.threads),
                                 film_.stats, spp, adaptive);
            is.denoise_seconds += std::chrono::duration<double>(Clock::now() - start_map).count();
            if (allocation->total == 0) {  // every pixel met the noise threshold
                rs_.converged = true;
                return false;
            }
        }
        return true;
    }

    // The iteration's samples [iteration_begin, iteration_end) in passes. False when the
    // render stopped inside it (tiles skipped, or a stop at a checkpoint's pass boundary).
    bool render_passes(std::uint64_t iteration_begin, std::uint64_t iteration_end, bool may_stop,
                       const std::optional<SampleAllocation>& allocation, IterationStats& is)
    {
        std::uint64_t next = std::max(iteration_begin, settings_.samples_done);
        while (next < iteration_end) {
            const int pass = in_passes_ && !steered_
                                 ? pass_samples(settings_.checkpoint_seconds, samples_per_second_,
                                                npix_, iteration_end - next)
                                 : int(iteration_end - next);
            const auto pass_start = Clock::now();
            // A checkpointing render stops only at pass boundaries, with whole passes.
            const detail::PassCounts done =
                detail::render_pass(pass_, next, pass, allocation ? &allocation->counts : nullptr,
                                    cancel_, may_stop && !in_passes_);
            rs_.tile_cycles += done.tile_cycles;
            rs_.bounce_cycles += done.bounce_cycles;
            rs_.samples += done.samples;
            is.samples += done.samples;
            const double seconds = std::chrono::duration<double>(Clock::now() - pass_start).count();
            if (seconds > 0)
                samples_per_second_ = double(done.samples) / seconds;
            const std::uint64_t expected =
                allocation ? allocation->total : std::uint64_t(pass) * npix_;
            if (done.samples < expected) {  // tiles skipped: a partial iteration
                rs_.interrupted = true;
                ++rs_.iterations_done;
                return false;
            }
            next += std::uint64_t(pass);
            // A stop on the last pass finds the render complete: it is written, not saved.
            if (in_passes_ && cancel_ && cancel_->load() && next < schedule_total_) {
                save(next);
                rs_.interrupted = true;
                return false;
            }
            if (in_passes_ && next < schedule_total_ &&
                std::chrono::duration<double>(Clock::now() - last_checkpoint_).count() >=
                    settings_.checkpoint_seconds)
                save(next);
        }
        return true;
    }

    void save(std::uint64_t done)
    {
        if (checkpoint_ && done > checkpointed_) {
            checkpoint_(film_, done);
            checkpointed_ = done;
        }
        last_checkpoint_ = Clock::now();
    }

    const Clock::time_point start_ = Clock::now();
    const RenderSettings& settings_;
    Film& film_;
    const std::atomic<bool>* cancel_;
    const IterationCallback& after_iteration_;
    const CheckpointCallback& checkpoint_;
    const PathIntegrator integrator_;
    const std::size_t npix_;
    const std::uint64_t schedule_total_;
    const bool tracks_bounces_, steered_, in_passes_;
    Progress progress_;
    std::optional<BounceEstimates> estimates_;
    detail::TilePass pass_;
    RenderStats rs_;
    Clock::time_point last_checkpoint_ = Clock::now();
    std::uint64_t checkpointed_;
    double samples_per_second_ = 0;
};

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
        stats =
            RenderLoop(scene, camera, settings, film, cancel, after_iteration, checkpoint).run();
    });
    return stats;
}

}  // namespace statmc::render
