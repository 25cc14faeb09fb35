#include "statmc/farm/job_record.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "statmc/layers/atomic_file.h"

namespace statmc::farm {

namespace {

constexpr const char* kFirstLine = "statmc-farm job 1";

}  // namespace

std::string job_record_path(const std::string& job_dir) { return job_dir + "/statmc-farm.job"; }

void write_job_record(const JobRecord& record)
{
    std::ostringstream text;
    text << kFirstLine << "\n"
         << "tasks\t" << record.job.tasks << "\n"
         << "render\t" << record.render_job << "\n";
    for (std::size_t i = 0; i < record.job.frames.size(); ++i) {
        const Frame& f = record.job.frames[i];
        text << "frame\t" << f.number << "\t" << record.merge_jobs.at(i) << "\t" << f.scene << "\t"
             << f.output << "\n";
    }
    layers::write_text_file_atomically(job_record_path(record.job.job_dir), text.str());
}

JobRecord read_job_record(const std::string& job_dir)
{
    const std::string path = job_record_path(job_dir);
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path + ": no job record here (statmc-farm submit writes it; "
                                        "give its --job-dir)");
    auto malformed = [&](int line) {
        return std::runtime_error(path + ":" + std::to_string(line) + ": not a statmc-farm job record");
    };
    JobRecord record;
    record.job.job_dir = job_dir;
    std::string line;
    int number = 0;
    if (!std::getline(in, line) || line != kFirstLine)
        throw malformed(1);
    number = 1;
    while (std::getline(in, line)) {
        ++number;
        std::vector<std::string> fields;
        std::istringstream split(line);
        for (std::string field; std::getline(split, field, '\t');)
            fields.push_back(field);
        try {
            if (fields.size() == 2 && fields[0] == "tasks")
                record.job.tasks = std::stoi(fields[1]);
            else if (fields.size() == 2 && fields[0] == "render")
                record.render_job = fields[1];
            else if (fields.size() == 5 && fields[0] == "frame") {
                record.job.frames.push_back({std::stoi(fields[1]), fields[3], fields[4]});
                record.merge_jobs.push_back(fields[2]);
            } else
                throw malformed(number);
        } catch (const std::logic_error&) {  // stoi
            throw malformed(number);
        }
    }
    if (record.render_job.empty() || record.job.frames.empty() || record.job.tasks < 1)
        throw malformed(number);
    return record;
}

}  // namespace statmc::farm
