// The state commands share while the program runs.
#pragma once

#include <map>
#include <memory>
#include <ostream>
#include <string>

#include <OpenImageIO/color.h>

#include "image_stack.h"
#include "statmc/layers/exr_files.h"

namespace statmc::tool {

struct ToolContext {
    explicit ToolContext(std::ostream& output) : out(output) {}

    std::ostream& out;  ///< where --help, --version and the reports print
    ImageStack stack;
    int nthreads = 0;   ///< --threads; 0 = all
    int exit_code = 0;  ///< 1 once a --diff has failed; the commands after it still run

    // oiiotool's flags, each affecting the commands after it.
    bool all_subimages = false;   ///< -a
    bool verbose = false;         ///< -v
    bool print_info = false;      ///< --info: report each input as it is read
    bool info_verbose = false;    ///< --info:verbose=1, as -v does for --info
    bool print_stats = false;     ///< --stats
    layers::WriteOptions output;  ///< -d, --compression
    layers::ReadOptions input;    ///< --max-memory, --check-inputs
    std::string colorconfig;      ///< --colorconfig; empty = $OCIO, else OIIO's built-in
    /// The loaded colorconfig: made by --colorconfig, else by the first colour command
    /// (not const: ImageBufAlgo 2.4 takes a ColorConfig*).
    std::shared_ptr<OIIO::ColorConfig> color_config;

    /// In a sequence run (sequence_run.h): the frame's input files and the sequences they
    /// belong to, which -i links to the images it reads.
    struct SequenceInput {
        std::shared_ptr<FrameSequence> sequence;
        int frame = 0;
    };
    std::map<std::string, SequenceInput> sequence_inputs;
};

}  // namespace statmc::tool
