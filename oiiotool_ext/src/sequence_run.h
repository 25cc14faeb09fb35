// Running a command line over a frame sequence, as oiiotool does: every -i and -o whose
// file name holds a frame pattern (shot.#.exr, shot.@@@.exr, shot.%04d.exr) names one file
// per frame, and the whole program runs once per frame of --frames (or of the files the
// first input pattern finds on disk), each with a fresh stack.
#pragma once

#include <functional>
#include <vector>

#include "statmc/tool/command.h"
#include "tool_context.h"

namespace statmc::tool {

/// A program prepared for its frames: per frame, the invocations with the frame's file
/// names, and the inputs that -i links to their sequences.
class SequenceRun {
public:
    /// Removes --frames and --skip-missing from `program` and resolves the frames.
    /// `active()` is false for a program without frame patterns. Throws HostError for
    /// --frames without a pattern, a pattern with no frames, or (without --skip-missing)
    /// a missing input frame; with it, a note on `err` names each frame skipped.
    SequenceRun(std::vector<Invocation> program, std::ostream& err);

    bool active() const { return !frames_.empty(); }
    const std::vector<int>& frames() const { return frames_; }

    /// The program for `frame`, and in `ctx` the inputs it reads from sequences.
    std::vector<Invocation> program_for(int frame, ToolContext& ctx) const;
    /// Drops the frames held that `frame` no longer needs.
    void advance_to(int frame) const;

    /// The program as given, for a run without patterns.
    const std::vector<Invocation>& program() const { return program_; }

private:
    std::vector<Invocation> program_;
    std::vector<int> frames_;
    std::vector<std::string> patterns_;  // per invocation: the printf pattern, or ""
    std::vector<std::shared_ptr<FrameSequence>> sequences_;  // per invocation (inputs)
};

}  // namespace statmc::tool
