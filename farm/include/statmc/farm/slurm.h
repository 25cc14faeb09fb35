// Slurm's commands as the farm front end runs them: sbatch to submit, squeue for the
// state of running and pending array elements. Every failure names the command and says
// what it printed.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace statmc::farm {

struct CommandResult {
    int status = 0;      ///< exit status; 127 when the program could not be started
    std::string out;     ///< standard output
    std::string err;     ///< standard error
};

/// Runs `argv` (argv[0] looked up on PATH) without a shell. Throws std::runtime_error when
/// the program cannot be started ("sbatch: cannot run it: No such file or directory; is it installed and on PATH?").
CommandResult run_command(const std::vector<std::string>& argv);

/// `sbatch --parsable [options] script [script_args]`; returns the job id. Throws
/// std::runtime_error with sbatch's message when it fails.
std::string submit(const std::string& script, const std::vector<std::string>& options,
                   const std::vector<std::string>& script_args = {});

/// The state of each pending or running element of the jobs in `job_ids` ("123_4" ->
/// "RUNNING"), from `squeue -r`. Jobs no longer queued are absent.
std::map<std::string, std::string> queued_states(const std::vector<std::string>& job_ids);

/// Final states from `sacct` ("123_4" -> "COMPLETED"); empty when accounting is not
/// configured on the cluster (sacct then fails), in which case the caller looks at files.
std::map<std::string, std::string> accounted_states(const std::vector<std::string>& job_ids);

}  // namespace statmc::farm
