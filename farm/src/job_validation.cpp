#include "statmc/farm/job_validation.h"

#include <stdexcept>

#include "statmc/farm/slurm.h"

namespace statmc::farm {

namespace {

std::string trimmed(const std::string& text)
{
    const auto end = text.find_last_not_of(" \n\r\t");
    return end == std::string::npos ? "" : text.substr(0, end + 1);
}

}  // namespace

std::vector<std::string> render_validation(const FarmJob& job, const Frame& frame)
{
    std::vector<std::string> argv{job.render_exe, frame.scene, "-o", task_output(frame, 0),
                                  "--task", "0/" + std::to_string(job.tasks)};
    if (job.spp > 0)
        argv.insert(argv.end(), {"--spp", std::to_string(job.spp)});
    argv.insert(argv.end(), {"--seed", std::to_string(frame_seed(job, frame)), "--checkpoint",
                             number_text(job.checkpoint_seconds), "--resume", "-q"});
    argv.insert(argv.end(), job.render_args.begin(), job.render_args.end());
    argv.push_back("--validate");
    return argv;
}

std::vector<std::string> merge_validation(const FarmJob& job, const Frame& frame)
{
    std::vector<std::string> argv{job.statmc_exe};
    for (int t = 0; t < job.tasks; ++t)
        argv.push_back(task_output(frame, t));
    argv.insert(argv.end(), {"--merge", "-o", frame.output});
    if (job.denoise)
        argv.insert(argv.end(), {"--denoise" + job.denoise_modifiers, "-o", denoised_output(frame)});
    argv.push_back("--validate");
    return argv;
}

void validate_job(const FarmJob& job)
{
    for (const Frame& frame : job.frames)
        for (const auto& argv : {render_validation(job, frame), merge_validation(job, frame)}) {
            const CommandResult r = run_command(argv);
            if (r.status != 0)
                throw std::runtime_error(
                    "frame " + std::to_string(frame.number) + ": " + argv[0] +
                    " would fail in the " + (argv[0] == job.render_exe ? "render" : "merge") +
                    " job (exit status " + std::to_string(r.status) +
                    "), so nothing was submitted: " + trimmed(r.err.empty() ? r.out : r.err));
        }
}

}  // namespace statmc::farm
