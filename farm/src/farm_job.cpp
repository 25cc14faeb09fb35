#include "statmc/farm/farm_job.h"

#include <cstdio>
#include <filesystem>

#include "statmc/layers/sample_provenance.h"

namespace statmc::farm {

namespace {

std::string with_suffix(const std::string& path, const std::string& suffix)
{
    std::filesystem::path p(path);
    const std::string ext = p.has_extension() ? p.extension().string() : ".exr";
    p.replace_extension();
    return p.string() + suffix + ext;
}

// "#SBATCH" lines for the options the user gave.
std::string slurm_lines(const SlurmOptions& s)
{
    std::string text;
    auto line = [&](const char* option, const std::string& value) {
        if (!value.empty())
            text += "#SBATCH --" + std::string(option) + "=" + value + "\n";
    };
    line("partition", s.partition);
    line("time", s.time);
    line("mem", s.mem);
    line("account", s.account);
    if (s.cpus_per_task > 0)
        line("cpus-per-task", std::to_string(s.cpus_per_task));
    return text;
}

// A bash array of `values`, one per line.
std::string bash_array(const std::string& name, const std::vector<std::string>& values)
{
    std::string text = name + "=(\n";
    for (const std::string& v : values)
        text += "  " + shell_quote(v) + "\n";
    return text + ")\n";
}

// The lines every statmc-farm script starts with: what it is, its job name, its log (in
// append mode, so a requeued job adds to its log), the user's Slurm options.
std::string script_header(const std::string& what, const std::string& name,
                          const std::string& log, const FarmJob& job)
{
    return "#!/bin/bash\n# statmc-farm: " + what +
           " Written by statmc-farm submit (docs/farm.md).\n#SBATCH --job-name=" + name +
           "\n#SBATCH --open-mode=append\n#SBATCH --output=" + job.job_dir + "/logs/" + log +
           "\n" + slurm_lines(job.slurm);
}

}  // namespace

std::string number_text(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string shell_quote(const std::string& text)
{
    std::string out = "'";
    for (char c : text)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string task_output(const Frame& frame, int task)
{
    return with_suffix(frame.output, ".task" + std::to_string(task));
}

int frame_seed(const FarmJob& job, const Frame& frame)
{
    return layers::frame_seed(job.seed, frame.number);
}

std::string denoised_output(const Frame& frame) { return with_suffix(frame.output, ".denoised"); }

std::string render_script(const FarmJob& job)
{
    std::vector<std::string> scenes, seeds, outputs;
    for (const Frame& f : job.frames) {
        scenes.push_back(f.scene);
        seeds.push_back(std::to_string(frame_seed(job, f)));
        for (int t = 0; t < job.tasks; ++t)
            outputs.push_back(task_output(f, t));
    }
    std::string extra;
    for (const std::string& a : job.render_args)
        extra += " " + shell_quote(a);
    const int elements = int(job.frames.size()) * job.tasks;
    const std::string n = std::to_string(job.tasks);
    std::string s = script_header("render tasks. Element k renders task k % " + n +
                                      " of frame k / " + n + ".",
                                  "statmc-render", "render-%a.log", job);
    s += "#SBATCH --array=0-" + std::to_string(elements - 1) + "\n";
    s += "#SBATCH --requeue\n";
    s += "set -u\n";
    s += bash_array("scenes", scenes);
    s += bash_array("seeds", seeds);
    s += bash_array("outputs", outputs);
    s += "k=${SLURM_ARRAY_TASK_ID:?run this script with sbatch}\n";
    s += "frame=$((k / " + n + ")); task=$((k % " + n + "))\n";
    s += "attempt=$((${SLURM_RESTART_COUNT:-0} + 1))\n";
    // Slurm's SIGTERM (time limit, preemption, scancel) reaches this shell too: with a trap
    // it waits for the render, which saves its checkpoint and exits 130, and goes on below.
    s += "trap 'echo \"statmc-farm: $(date -Is) SIGTERM: the render saves its checkpoint\"' "
         "TERM INT\n";
    s += "echo \"statmc-farm: $(date -Is) ${SLURM_ARRAY_JOB_ID}_${k} on $(hostname):\"\\\n"
         "     \"task $task/" + n + " of ${scenes[$frame]}, attempt $attempt\"\n";
    s += shell_quote(job.render_exe) + " \"${scenes[$frame]}\" -o \"${outputs[$k]}\" --task \"$task/" +
         n + "\"" + (job.spp > 0 ? " --spp " + std::to_string(job.spp) : std::string()) +
         " --seed \"${seeds[$frame]}\" --checkpoint " + number_text(job.checkpoint_seconds) +
         " --resume --threads \"${SLURM_CPUS_PER_TASK:-0}\" -q" + extra + "\n";
    s += "status=$?\n";
    // Killed (SIGKILL, the OOM killer) or stopped (SIGTERM: the render saved its film and
    // exited 130): run again from the checkpoint. Errors (status 1) are not retried.
    s += "if [ \"$status\" -ge 128 ] && [ \"${SLURM_RESTART_COUNT:-0}\" -lt " +
         std::to_string(job.max_restarts) + " ]; then\n";
    s += "  echo \"statmc-farm: the render stopped with status $status; requeueing it to resume\"\\\n"
         "       \"from its checkpoint\"\n";
    s += "  scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${k}\"\n";
    s += "fi\n";
    s += "exit \"$status\"\n";
    return s;
}

std::string merge_script(const FarmJob& job)
{
    std::vector<std::string> outputs, denoised, tasks;
    for (const Frame& f : job.frames) {
        outputs.push_back(f.output);
        denoised.push_back(denoised_output(f));
        for (int t = 0; t < job.tasks; ++t)
            tasks.push_back(task_output(f, t));
    }
    const std::string n = std::to_string(job.tasks);
    std::string s = script_header("merge (and denoise) one frame's tasks; the argument is the "
                                  "frame's index.",
                                  "statmc-merge", "merge-%j.log", job);
    s += "set -euo pipefail\n";
    s += bash_array("outputs", outputs);
    s += bash_array("denoised", denoised);
    s += bash_array("tasks", tasks);
    s += "frame=${1:?the frame index}\n";
    s += "echo \"statmc-farm: $(date -Is) merging ${outputs[$frame]}\"\n";
    s += shell_quote(job.statmc_exe) + " \"${tasks[@]:$((frame * " + n + ")):" + n +
         "}\" --merge -o \"${outputs[$frame]}\"";
    if (job.denoise)
        s += " " + shell_quote("--denoise" + job.denoise_modifiers) + " -o \"${denoised[$frame]}\"";
    s += "\n";
    return s;
}

}  // namespace statmc::farm
