// statmc-farm: renders frames on a Slurm cluster. `submit` writes the batch scripts (a
// render job array of N tasks per frame, one merge+denoise job per frame that waits for
// its tasks) and submits them with sbatch; `status` reports each frame's tasks
// (docs/farm.md). Slurm does the scheduling, requeueing and dependencies.
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "statmc/farm/farm_job.h"
#include "statmc/farm/frame_pattern.h"
#include "statmc/farm/job_record.h"
#include "statmc/farm/job_validation.h"
#include "statmc/farm/slurm.h"
#include "statmc/layers/atomic_file.h"

namespace {

namespace fs = std::filesystem;
using namespace statmc::farm;

// A program statmc-farm drives: beside statmc-farm itself (an installation), else where
// this build put it, else on PATH.
std::string find_program(const std::string& name, const std::string& built_at)
{
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (!ec && fs::exists(self.parent_path() / name))
        return (self.parent_path() / name).string();
    if (fs::exists(built_at))
        return built_at;
    return name;
}

std::string absolute(const std::string& path)
{
    return fs::absolute(path).lexically_normal().string();
}

std::vector<Frame> frames_of(const std::vector<std::string>& scenes, const std::string& frames,
                             const std::string& output)
{
    std::vector<Frame> out;
    if (!frames.empty()) {
        if (scenes.size() != 1 || !has_frame_number(scenes[0]))
            throw std::runtime_error("--frames needs one SCENE with a frame number, such as "
                                     "shot.%04d.pbrt");
        if (!has_frame_number(output))
            throw std::runtime_error("-o " + output +
                                     ": a sequence needs a frame number in the "
                                     "output, such as out/shot.%04d.exr");
        for (int f : parse_frames(frames))
            out.push_back({f, expand_frame(scenes[0], f), expand_frame(output, f)});
    } else {
        if (scenes.size() > 1 && !has_frame_number(output))
            throw std::runtime_error("-o " + output +
                                     ": several scenes need a frame number in "
                                     "the output (their position in the list), such as "
                                     "out/frame.%02d.exr");
        for (std::size_t i = 0; i < scenes.size(); ++i)
            out.push_back({int(i), scenes[i],
                           has_frame_number(output) ? expand_frame(output, int(i)) : output});
    }
    for (Frame& f : out) {
        if (!fs::is_regular_file(f.scene))
            throw std::runtime_error("frame " + std::to_string(f.number) + ": scene " + f.scene +
                                     " does not exist");
        const fs::path dir = fs::absolute(f.output).parent_path();
        if (!fs::is_directory(dir))
            throw std::runtime_error("frame " + std::to_string(f.number) + ": output directory " +
                                     dir.string() + " does not exist");
        f.scene = absolute(f.scene);
        f.output = absolute(f.output);
    }
    return out;
}

void write_script(const std::string& path, const std::string& text)
{
    statmc::layers::write_text_file_atomically(path, text);
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

// Element ids of frame i's tasks, "J_k:J_k+1:...", for --dependency=afterok.
std::string task_elements(const std::string& render_job, std::size_t frame, int tasks)
{
    std::string ids;
    for (int t = 0; t < tasks; ++t)
        ids += (t ? ":" : "") + render_job + "_" + std::to_string(frame * tasks + t);
    return ids;
}

// sbatch's options for frame i's merge: after its tasks, removed when one fails for good.
std::vector<std::string> merge_options(const std::string& render_job, std::size_t frame,
                                       int tasks)
{
    return {"--kill-on-invalid-dep=yes",
            "--dependency=afterok:" + task_elements(render_job, frame, tasks)};
}

// A value that goes into an #SBATCH line: one line, no spaces, and no '%' (Slurm expands
// it in --output paths).
void require_sbatch_value(const std::string& option, const std::string& value)
{
    if (value.find_first_of("\n\r \t%") != std::string::npos)
        throw std::runtime_error(option + " '" + value +
                                 "': Slurm options and the job directory may not hold spaces, "
                                 "line breaks or '%'");
}

int submit_job(FarmJob job, bool dry_run)
{
    require_sbatch_value("--partition", job.slurm.partition);
    require_sbatch_value("--time", job.slurm.time);
    require_sbatch_value("--mem", job.slurm.mem);
    require_sbatch_value("--account", job.slurm.account);
    require_sbatch_value("--job-dir", job.job_dir);
    const std::string render = job.job_dir + "/render.sbatch",
                      merge = job.job_dir + "/merge.sbatch";
    validate_job(job);
    if (dry_run) {
        std::printf("# %s\n%s\n# %s\n%s\n", render.c_str(), render_script(job).c_str(),
                    merge.c_str(), merge_script(job).c_str());
        std::printf("# would run: sbatch --parsable %s\n", render.c_str());
        for (std::size_t i = 0; i < job.frames.size(); ++i) {
            std::string line = "sbatch --parsable";
            for (const std::string& option : merge_options("<render job>", i, job.tasks))
                line += " " + option;
            std::printf("# would run: %s %s %zu\n", line.c_str(), merge.c_str(), i);
        }
        return 0;
    }
    fs::create_directories(job.job_dir + "/logs");
    write_script(render, render_script(job));
    write_script(merge, merge_script(job));
    JobRecord record{job, submit(render, {}), {}};
    std::printf("statmc-farm: render job %s: %zu frame(s) x %d task(s)\n",
                record.render_job.c_str(), job.frames.size(), job.tasks);
    for (std::size_t i = 0; i < job.frames.size(); ++i) {
        try {
            record.merge_jobs.push_back(
                submit(merge, merge_options(record.render_job, i, job.tasks), {std::to_string(i)}));
        } catch (const std::runtime_error& e) {
            // No job left behind that nothing follows: the renders and merges go too.
            std::vector<std::string> cancel{"scancel", record.render_job};
            cancel.insert(cancel.end(), record.merge_jobs.begin(), record.merge_jobs.end());
            run_command(cancel);
            throw std::runtime_error(std::string(e.what()) +
                                     "; cancelled the jobs submitted so far (" + record.render_job +
                                     " and its merges)");
        }
        std::printf("statmc-farm: merge job %s -> %s\n", record.merge_jobs.back().c_str(),
                    job.frames[i].output.c_str());
    }
    write_job_record(record);
    std::printf("statmc-farm: follow it with: statmc-farm status --job-dir %s\n",
                job.job_dir.c_str());
    return 0;
}

// Per frame: tasks done (their output exists), running, pending, failed; and the merge.
int report_status(const std::string& job_dir)
{
    const JobRecord record = read_job_record(absolute(job_dir));
    std::vector<std::string> ids{record.render_job};
    ids.insert(ids.end(), record.merge_jobs.begin(), record.merge_jobs.end());
    const auto queued = queued_states(ids);
    const auto accounted = accounted_states(ids);
    int unfinished = 0, failed_frames = 0;
    for (std::size_t i = 0; i < record.job.frames.size(); ++i) {
        const Frame& f = record.job.frames[i];
        int done = 0, running = 0, pending = 0, failed = 0;
        for (int t = 0; t < record.job.tasks; ++t) {
            const std::string element =
                record.render_job + "_" + std::to_string(i * record.job.tasks + t);
            const auto q = queued.find(element);
            const auto a = accounted.find(element);
            if (fs::exists(task_output(f, t)))
                ++done;
            else if (q != queued.end())
                ++(q->second == "RUNNING" ? running : pending);
            else if (a != accounted.end() && (a->second == "RUNNING" || a->second == "PENDING"))
                ++(a->second == "RUNNING" ? running : pending);
            else  // neither queued nor written: it ended without its output
                ++failed;
        }
        std::string merge = "waiting";
        const auto q = queued.find(record.merge_jobs[i]);
        if (fs::exists(f.output))
            merge = "merged";
        else if (q != queued.end())
            merge = q->second == "RUNNING" ? "merging"
                                           : (failed ? "blocked (a task failed)" : "waiting");
        else
            merge = "failed (see " + record.job.job_dir + "/logs)";
        unfinished += merge != "merged";
        failed_frames += merge.rfind("failed", 0) == 0 || merge.rfind("blocked", 0) == 0 ||
                         (failed > 0 && merge != "merged");
        std::printf("frame %d: %d/%d tasks done, %d running, %d pending, %d failed; %s: %s\n",
                    f.number, done, record.job.tasks, running, pending, failed, merge.c_str(),
                    f.output.c_str());
    }
    return unfinished == 0 ? 0 : failed_frames > 0 ? 2 : 3;
}

// Whether statmc --denoise modifiers (":k=v:k=v") ask for temporal=K with K > 0.
bool asks_for_temporal(const std::string& modifiers)
{
    std::size_t start = 0;
    while (start < modifiers.size()) {
        std::size_t end = modifiers.find(':', start + 1);
        if (end == std::string::npos)
            end = modifiers.size();
        const std::string item = modifiers.substr(start + 1, end - start - 1);
        if (item.rfind("temporal=", 0) == 0 && item.find_first_not_of('0', 9) != std::string::npos)
            return true;
        start = end;
    }
    return false;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"statmc-farm: render frames on a Slurm cluster as tasks that merge exactly "
                 "(docs/farm.md)"};
    app.require_subcommand(1);

    FarmJob job;
    std::vector<std::string> scenes;
    std::string frames, output, job_dir, denoise_options;
    bool dry_run = false;
    CLI::App* submit_cmd = app.add_subcommand(
        "submit", "write the batch scripts and submit them with sbatch: a render job array (N "
                  "tasks per frame, checkpointed, requeued when killed) and one merge job per "
                  "frame that runs when its tasks have succeeded");
    submit_cmd
        ->add_option("scene", scenes,
                     "pbrt scene(s); with --frames one printf pattern (shot.%04d.pbrt)")
        ->required();
    submit_cmd
        ->add_option("-o,--output", output,
                     "the merged statistics EXR of each frame; a printf pattern "
                     "(out/shot.%04d.exr) for a sequence")
        ->required();
    submit_cmd->add_option("--tasks", job.tasks, "tasks per frame")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    submit_cmd
        ->add_option("--spp", job.spp, "samples per pixel of each frame [default: the scene's]")
        ->check(CLI::Range(1, 1 << 30));
    submit_cmd->add_option("--frames", frames, "frame range A-B of a sequence [default: unset]");
    submit_cmd->add_option("--seed", job.seed, "random seed, mixed with each frame's number so frames have independent noise")
        ->capture_default_str()
        ->check(CLI::Range(0, 1 << 30));
    submit_cmd
        ->add_option("--checkpoint", job.checkpoint_seconds,
                     "seconds between a render task's checkpoints: what a killed task loses "
                     "at most")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    submit_cmd
        ->add_option("--max-restarts", job.max_restarts,
                     "times a killed render task is requeued before it counts as failed")
        ->capture_default_str()
        ->check(CLI::Range(0, 100));
    submit_cmd
        ->add_option("--denoise", denoise_options,
                     "also write OUT.denoised.exr per frame, with statmc --denoise modifiers "
                     "(method=classic:radius=10); give none for the default")
        ->expected(0, 1)
        ->default_str("");
    submit_cmd->add_option("--render-args", job.render_args,
                           "more statmc-render options for every task, e.g. "
                           "--render-args=--maxdepth --render-args=8 [default: none]");
    submit_cmd->add_option("--partition", job.slurm.partition, "Slurm partition");
    submit_cmd->add_option("--time", job.slurm.time, "Slurm time limit per job (e.g. 2:00:00)");
    submit_cmd->add_option("--mem", job.slurm.mem, "Slurm memory per job (e.g. 8G)");
    submit_cmd
        ->add_option("--cpus-per-task", job.slurm.cpus_per_task,
                     "Slurm CPUs per job; the render uses them all")
        ->check(CLI::Range(1, 4096));
    submit_cmd->add_option("--account", job.slurm.account, "Slurm account");
    submit_cmd->add_option("--job-dir", job_dir,
                           "where the scripts, logs and job record go [default: "
                           "statmc-farm/ beside the first output]");
    submit_cmd->add_flag("--dry-run", dry_run,
                         "print the scripts and sbatch commands; submit nothing");
    submit_cmd->add_option("--render-exe", job.render_exe, "statmc-render to run [default: found]");
    submit_cmd->add_option("--statmc-exe", job.statmc_exe, "statmc to run [default: found]");

    std::string status_dir;
    CLI::App* status_cmd = app.add_subcommand(
        "status", "per frame: render tasks done, running, pending and failed, and the merge "
                  "(from squeue, sacct where accounting runs, and the files); exit status 0 "
                  "once every frame is merged, 2 when a frame failed, 3 while in progress");
    status_cmd->add_option("--job-dir", status_dir, "the job directory of statmc-farm submit")
        ->required();

    CLI11_PARSE(app, argc, argv);
    try {
        if (status_cmd->parsed())
            return report_status(status_dir);
        job.frames = frames_of(scenes, frames, output);
        if (job.spp > 0 && job.tasks > job.spp)
            throw std::runtime_error("--tasks " + std::to_string(job.tasks) + " with --spp " +
                                     std::to_string(job.spp) +
                                     ": at most as many tasks as samples per pixel");
        job.denoise = submit_cmd->get_option("--denoise")->count() > 0;
        job.denoise_modifiers = denoise_options.empty() || denoise_options[0] == ':'
                                    ? denoise_options
                                    : ":" + denoise_options;
        if (asks_for_temporal(job.denoise_modifiers))
            throw std::runtime_error(
                "--denoise" + job.denoise_modifiers +
                ": each frame's merge denoises that frame alone, so temporal denoising would "
                "fail there after the renders; once every frame is merged, run statmc over the "
                "sequence: statmc OUT --frames LIST --denoise:temporal=K -o DENOISED "
                "(docs/farm.md)");
        job.job_dir =
            absolute(job_dir.empty()
                         ? (fs::path(job.frames[0].output).parent_path() / "statmc-farm").string()
                         : job_dir);
        if (job.render_exe.empty())
            job.render_exe = find_program("statmc-render", STATMC_RENDER_BUILT_AT);
        if (job.statmc_exe.empty())
            job.statmc_exe = find_program("statmc", STATMC_CLI_BUILT_AT);
        return submit_job(job, dry_run);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "statmc-farm: error: %s\n", e.what());
        return 1;
    }
}
