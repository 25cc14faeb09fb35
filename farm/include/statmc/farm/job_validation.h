// What statmc-farm checks before it submits: every frame's render and merge command, run
// with --validate by the very programs the jobs will run, so that a typo in a modifier or a
// render option fails at submit, not after a night of renders (docs/farm.md).
#pragma once

#include <string>
#include <vector>

#include "statmc/farm/farm_job.h"

namespace statmc::farm {

/// statmc-render's command line for task 0 of `frame`, as the render job runs it.
std::vector<std::string> render_validation(const FarmJob& job, const Frame& frame);
/// statmc's command line for the merge (and denoise) of `frame`, as the merge job runs it.
std::vector<std::string> merge_validation(const FarmJob& job, const Frame& frame);

/// Runs both for every frame. Throws std::runtime_error naming the frame, the program and
/// what it said, at the first that fails.
void validate_job(const FarmJob& job);

}  // namespace statmc::farm
