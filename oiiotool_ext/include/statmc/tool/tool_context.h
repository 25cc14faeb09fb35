// The state commands share while the program runs.
#pragma once

#include <ostream>

#include "statmc/tool/image_stack.h"

namespace statmc::tool {

struct ToolContext {
    explicit ToolContext(std::ostream& output) : out(output) {}

    std::ostream& out;  ///< where --help and --version print
    ImageStack stack;
    int nthreads = 0;   ///< --threads; 0 = all
};

}  // namespace statmc::tool
