#include "statmc/render/render_job.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "statmc/denoise/denoise.h"
#include "statmc/layers/atomic_file.h"
#include "statmc/layers/file_error.h"
#include "statmc/layers/layer_names.h"
#include "statmc/merge/merge.h"
#include "statmc/render/camera.h"
#include "statmc/render/checkpoint.h"
#include "statmc/render/exr_output.h"
#include "statmc/render/scene.h"

namespace statmc::render {

namespace {

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

// One frame of a job: its camera (and the previous frame's, for the motion layer), its
// shares of samples, its outputs and its report.
class FrameRender {
public:
    FrameRender(const RenderJob& job, const Scene& scene, const FrameToRender& frame,
                const std::atomic<bool>& interrupted)
        : job_(job), scene_(scene), frame_(frame), interrupted_(interrupted),
          settings_(job.settings),
          camera_(job.scene.camera.at_time(frame.time), settings_.width, settings_.height),
          frame_spp_(int(schedule_samples(job.settings.schedule))),
          steering_(bounce_layout_for(job.settings.integrator)),
          layers_(bounce_layers_for(job.settings.integrator, job.bounce_layers))
    {
        settings_.seed = std::uint64_t(frame.seed);
        if (frame.number)
            previous_.emplace(job.scene.camera.at_time(frame.time - 1 / job.fps), settings_.width,
                              settings_.height);
        settings_.previous_camera = previous_ ? &*previous_ : nullptr;
    }
    FrameRender(const FrameRender&) = delete;
    FrameRender& operator=(const FrameRender&) = delete;

    // Renders and writes the frame; the process's exit status.
    int run()
    {
        RenderStats stats;
        Film::SampleCounts counts;
        const int status = job_.tasks > 0 ? render_tasks(stats, counts) : render_one(stats, counts);
        if (status != 0)
            return status;
        report(stats, counts);
        // A stop that came after the last sample changed nothing: the output is whole.
        return stats.interrupted && !stats.complete ? 130 : 0;
    }

private:
    struct Share {
        std::unique_ptr<Film> film;
        RenderStats stats;
        OutputInfo info;
    };

    double elapsed() const
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

    // The header of a film holding `task`'s samples after `seconds` of rendering.
    OutputInfo output_info(const Film& f, const RenderTask& task, double seconds) const
    {
        OutputInfo info;
        info.spp = f.sample_counts();
        info.provenance.seed = frame_.seed;
        info.provenance.range = task_samples(frame_spp_, task);
        // Pixel p holds sample indices 0 .. n_p − 1: the range covers them all.
        if (settings_.adaptive.enabled)
            info.provenance.range->end = info.provenance.range->begin + info.spp.max;
        if (!job_.whole_frame) {
            info.provenance.task_index = task.index;
            info.provenance.task_count = task.count;
        }
        info.render_seconds = float(seconds);
        info.scene = job_.scene_path;
        info.higher_moments = job_.higher_moments;
        info.frame = frame_.number;
        return info;
    }

    // Writes the film to the checkpoint, keeping the previous one when that fails.
    CheckpointCallback checkpoint_saver(const CheckpointIdentity& identity,
                                        const double& seconds_before) const
    {
        if (job_.checkpoint_seconds <= 0)
            return {};
        return [this, identity, &seconds_before](const Film& f, std::uint64_t samples_done) {
            try {
                write_checkpoint(checkpoint_path(frame_.output), f, identity,
                                 {samples_done, seconds_before + elapsed()});
            } catch (const statmc::layers::FileError& e) {
                // The render goes on; the previous checkpoint, if any, is intact.
                std::fprintf(stderr,
                             "statmc-render: warning: %s; the previous checkpoint is kept and the "
                             "render continues\n",
                             e.what());
            }
        };
    }

    // One share of the frame's samples (`task`; 0/1 for the whole) into a film of its own,
    // resumed from the checkpoint when asked.
    Share render_share(const RenderTask& task, const IterationCallback& after_iteration)
    {
        const statmc::layers::SampleRange range = task_samples(frame_spp_, task);
        RenderSettings share = settings_;
        if (!job_.whole_frame)
            share.schedule = schedule_for_spp(range.count());
        share.first_sample = std::uint64_t(range.begin);
        share.checkpoint_seconds = job_.checkpoint_seconds;
        auto film = std::make_unique<Film>(share.width, share.height, steering_, layers_);
        if (share.previous_camera)
            film->track_motion();
        const CheckpointIdentity identity{
            job_.scene_path, job_.scene.source_crc,
            frame_.seed,     share.width,
            share.height,    task.index,
            task.count,      range.begin,
            range.end,       settings_text(share, job_.bounce_layers)};
        const std::string checkpoint = checkpoint_path(frame_.output);
        double seconds_before = 0;
        if (job_.resume && std::filesystem::exists(checkpoint)) {
            const CheckpointProgress done = read_checkpoint(checkpoint, *film, identity);
            share.samples_done = done.samples_done;
            seconds_before = done.render_seconds;
            std::fprintf(stderr,
                         "%s: resuming from checkpoint %s: %llu of %d samples per pixel done\n",
                         frame_.output.c_str(), checkpoint.c_str(),
                         static_cast<unsigned long long>(done.samples_done), range.count());
        }
        const RenderStats stats =
            render(scene_, camera_, share, *film, &interrupted_, after_iteration,
                   checkpoint_saver(identity, seconds_before));
        const OutputInfo info = output_info(*film, task, seconds_before + stats.seconds);
        return {std::move(film), stats, info};
    }

    void write_outputs(const OIIO::ImageBuf& image) const
    {
        write_exr(image, frame_.output);
        if (!job_.denoise)
            return;
        OIIO::ImageBuf denoised;
        const statmc::DenoiseImageOptions options;
        if (!statmc::denoise(denoised, image, options))
            throw std::runtime_error("denoise: " + denoised.geterror());
        write_exr(denoised, denoised_path(frame_.output));
    }

    // The tasks one after another, merged in task order as statmc --merge would.
    int render_tasks(RenderStats& stats, Film::SampleCounts& counts)
    {
        std::vector<OIIO::ImageBuf> parts;
        for (int t = 0; t < job_.tasks && !interrupted_.load(); ++t) {
            Share part = render_share({t, job_.tasks}, {});
            stats.samples += part.stats.samples;
            stats.seconds += part.stats.seconds;
            stats.tile_cycles += part.stats.tile_cycles;
            if (part.stats.interrupted)
                break;
            parts.push_back(make_output_image(*part.film, part.info));
        }
        statmc::layers::install_write_signal_handlers();
        if (int(parts.size()) < job_.tasks) {
            std::fprintf(stderr,
                         "statmc-render: interrupted after %zu of %d tasks; %s not written\n",
                         parts.size(), job_.tasks, frame_.output.c_str());
            return 130;
        }
        OIIO::ImageBuf merged = merge_tasks(parts);
        merged.specmod().attribute(statmc::layers::attr::kRenderTime, float(stats.seconds));
        merged.specmod().attribute(statmc::layers::attr::kScene, job_.scene_path);
        write_outputs(merged);
        counts = Film::SampleCounts{frame_spp_, frame_spp_, double(frame_spp_), true};
        return 0;
    }

    // The frame, or the job's task of it, in one film.
    int render_one(RenderStats& stats, Film::SampleCounts& counts)
    {
        IterationCallback after_iteration;
        if (job_.every_iteration)
            after_iteration = [this](int, const Film& f, const IterationStats&) {
                OutputInfo info = output_info(f, job_.task, elapsed());
                // The samples so far, not the whole range.
                info.provenance.range->end = info.provenance.range->begin + info.spp.min;
                write_outputs(make_output_image(f, info));
            };
        Share share = render_share(job_.task, after_iteration);
        statmc::layers::install_write_signal_handlers();
        stats = share.stats;
        counts = share.info.spp;
        if (job_.checkpoint_seconds > 0 && !stats.complete) {
            // The film is saved; an output now would be a partial task that merges wrongly.
            std::fprintf(stderr,
                         "statmc-render: interrupted: %s holds the render so far; run again with "
                         "--resume to finish %s\n",
                         checkpoint_path(frame_.output).c_str(), frame_.output.c_str());
            return 130;
        }
        write_outputs(make_output_image(*share.film, share.info));
        if (stats.complete) {  // the output holds it all now
            std::error_code ignored;
            std::filesystem::remove(checkpoint_path(frame_.output), ignored);
        }
        return 0;
    }

    void report(const RenderStats& stats, const Film::SampleCounts& counts) const
    {
        const int width = settings_.width, height = settings_.height;
        const double rate = stats.seconds > 0 ? double(stats.samples) / stats.seconds * 1e-6 : 0.0;
        if (!job_.quiet && settings_.adaptive.enabled)
            std::fprintf(stderr,
                         "%s: %dx%d, adaptive: %.1f spp on average, %d to %d%s%s, %.2f s, "
                         "%.2f Msamples/s\n",
                         frame_.output.c_str(), width, height, counts.mean, counts.min, counts.max,
                         stats.converged ? ", every pixel within the noise threshold" : "",
                         stats.interrupted ? " (interrupted)" : "", stats.seconds, rate);
        else if (!job_.quiet)
            std::fprintf(stderr, "%s: %dx%d, %s%d spp%s, %.2f s, %.2f Msamples/s\n",
                         frame_.output.c_str(), width, height, counts.uniform ? "" : "at least ",
                         counts.min, stats.interrupted ? " (interrupted)" : "", stats.seconds,
                         rate);
        if (!job_.profile)
            return;
        const auto t = scene_.traversal_counters();
        std::printf("%s: %dx%d, %d spp, %zu triangles, threads %s\n", job_.scene_path.c_str(),
                    width, height, counts.min, scene_.triangle_count(),
                    settings_.threads > 0 ? std::to_string(settings_.threads).c_str() : "all");
        std::printf("  %.3f s, %.3f Msamples/s, %.2f Mrays/s, %.2f rays/sample\n", stats.seconds,
                    double(stats.samples) / stats.seconds * 1e-6,
                    double(t.rays) / stats.seconds * 1e-6,
                    stats.samples ? double(t.rays) / double(stats.samples) : 0.0);
        std::printf("  Embree traversal %.1f%% of render time, shading and the rest %.1f%%\n",
                    100.0 * double(t.cycles) / double(stats.tile_cycles),
                    100.0 - 100.0 * double(t.cycles) / double(stats.tile_cycles));
    }

    const RenderJob& job_;
    const Scene& scene_;
    const FrameToRender& frame_;
    const std::atomic<bool>& interrupted_;
    RenderSettings settings_;
    std::optional<Camera> previous_;
    Camera camera_;
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    int frame_spp_;
    BounceLayout steering_, layers_;
};

}  // namespace

std::string settings_text(const RenderSettings& s, bool bounce_layers)
{
    const auto& i = s.integrator;
    char text[256];
    std::snprintf(text, sizeof text,
                  "maxdepth %d, rr %d/%d/%d, mis %d/%d/%g, estimates radius %d, bounce layers "
                  "%s, %s, schedule",
                  i.maxdepth, int(i.roulette.mode), i.roulette.start_bounce,
                  i.roulette.tracked_bounces, int(i.mis.mode), i.mis.tracked_bounces,
                  double(i.mis.threshold), s.bounce_filter.radius, bounce_layers ? "all" : "none",
                  s.adaptive.text().c_str());
    std::string out = text;
    for (int n : s.schedule)
        out += " " + std::to_string(n);
    return out;
}

int run_render_job(const RenderJob& job, const Scene& scene, const std::atomic<bool>& interrupted)
{
    for (const FrameToRender& frame : job.frames)
        if (const int status = FrameRender(job, scene, frame, interrupted).run(); status != 0)
            return status;
    return 0;
}

}  // namespace statmc::render
