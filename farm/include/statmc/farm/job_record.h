// What statmc-farm submit leaves in the job directory for statmc-farm status: the job ids
// and, per frame, its scene, output and merge job.
#pragma once

#include <string>
#include <vector>

#include "statmc/farm/farm_job.h"

namespace statmc::farm {

struct JobRecord {
    FarmJob job;                          ///< frames and tasks (what status needs)
    std::string render_job;               ///< the render array's id
    std::vector<std::string> merge_jobs;  ///< one per frame
};

/// "<job_dir>/statmc-farm.job".
std::string job_record_path(const std::string& job_dir);

/// Writes the record atomically. Throws on failure.
void write_job_record(const JobRecord& record);

/// Reads the record in `job_dir`. Throws std::runtime_error naming the file when it is
/// missing or malformed.
JobRecord read_job_record(const std::string& job_dir);

}  // namespace statmc::farm
