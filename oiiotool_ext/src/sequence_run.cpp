#include "sequence_run.h"

#include <algorithm>
#include <ostream>

#include "statmc/layers/input_path.h"
#include "statmc/plugin_host/host_error.h"

namespace statmc::tool {

namespace {

bool is_file_command(const Invocation& inv) { return inv.name == "-i" || inv.name == "-o"; }

}  // namespace

SequenceRun::SequenceRun(std::vector<Invocation> program, std::ostream& err)
{
    std::string frames_spec;
    bool skip_missing = false, frames_given = false;
    for (Invocation& inv : program) {
        if (inv.name == "--frames") {
            frames_spec = inv.args[0];
            frames_given = true;
        } else if (inv.name == "--skip-missing") {
            skip_missing = true;
        } else {
            program_.push_back(std::move(inv));
        }
    }
    std::string first_input, first_pattern, written_range;
    for (const Invocation& inv : program_) {
        std::string range;
        patterns_.push_back(is_file_command(inv) ? frame_pattern(inv.args[0], &range) : "");
        if (!patterns_.back().empty() && inv.name == "-i" && first_input.empty()) {
            first_input = inv.args[0];
            first_pattern = patterns_.back();
        }
        if (written_range.empty())
            written_range = range;
    }
    const bool any_pattern =
        std::any_of(patterns_.begin(), patterns_.end(), [](const auto& p) { return !p.empty(); });
    if (!any_pattern) {
        if (frames_given || skip_missing)
            throw host::HostError(std::string(frames_given ? "--frames" : "--skip-missing") +
                                  ": no input or output names a frame pattern (shot.#.exr, "
                                  "shot.@@@.exr, shot.%04d.exr)");
        return;
    }
    std::vector<int> frames;
    if (frames_given)
        frames = parse_frame_list(frames_spec);
    else if (!written_range.empty())
        frames = parse_frame_list(written_range);
    else if (!first_pattern.empty())
        frames = frames_on_disk(first_input, first_pattern);
    else
        throw host::HostError("the outputs name a frame pattern but no input does: give --frames");

    // A frame runs only when every input pattern has its file (the readers' own check).
    for (int frame : frames) {
        std::string missing, why;
        for (std::size_t k = 0; k < program_.size() && why.empty(); ++k)
            if (program_[k].name == "-i" && !patterns_[k].empty()) {
                missing = frame_path(patterns_[k], frame);
                why = layers::input_path_problem(missing);
            }
        if (why.empty()) {
            frames_.push_back(frame);
        } else if (skip_missing) {
            err << "statmc: note: skipping frame " << frame << ": " << missing << ": " << why
                << "\n";
        } else {
            throw host::HostError(missing + ": frame " + std::to_string(frame) +
                                  " of the sequence is missing: " + why +
                                  " (--skip-missing skips such frames)");
        }
    }
    if (frames_.empty())
        throw host::HostError("no frame of the sequence has all its inputs");
    for (std::size_t k = 0; k < program_.size(); ++k)
        sequences_.push_back(program_[k].name == "-i" && !patterns_[k].empty()
                                 ? std::make_shared<FrameSequence>(patterns_[k], frames_)
                                 : nullptr);
}

std::vector<Invocation> SequenceRun::program_for(int frame, ToolContext& ctx) const
{
    std::vector<Invocation> program = program_;
    for (std::size_t k = 0; k < program.size(); ++k) {
        if (patterns_[k].empty())
            continue;
        program[k].args[0] = frame_path(patterns_[k], frame);
        if (sequences_[k])
            ctx.sequence_inputs[program[k].args[0]] = {sequences_[k], frame};
    }
    return program;
}

void SequenceRun::advance_to(int frame) const
{
    for (const auto& sequence : sequences_)
        if (sequence)
            sequence->forget_beyond_reach(frame);
}

}  // namespace statmc::tool
