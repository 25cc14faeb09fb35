// --frames and --skip-missing: how a command line with frame patterns runs over a
// sequence. The sequence run (sequence_run.h) reads them before any frame runs.
#include "frame_sequence.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_table.h"

namespace statmc::tool {

Command frames_command()
{
    Command c;
    c.name = "--frames";
    c.arg_names = {"LIST"};
    c.summary = "Run the command line once per frame of LIST (1-48, 1-48x2, 3,5,10-20): each "
                "-i and -o with a frame pattern (shot.#.exr = %04d, shot.@@@.exr = %03d, "
                "shot.%04d.exr) names that frame's file. Without --frames, the frames are "
                "the files the first input pattern matches";
    c.check = [](const Invocation& inv) { parse_frame_list(inv.args[0]); };
    c.run = [](ToolContext&, const Invocation&) {};  // consumed by the sequence run
    return c;
}

Command skip_missing_command()
{
    Command c;
    c.name = "--skip-missing";
    c.summary = "In a sequence, skip (with a note) the frames whose input files are missing; "
                "without it a missing frame is an error naming the file";
    c.run = [](ToolContext&, const Invocation&) {};  // consumed by the sequence run
    return c;
}

}  // namespace statmc::tool
