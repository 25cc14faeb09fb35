// statmc: the command-line host. Everything but argv handling lives in statmc_tool.
#include <iostream>
#include <string>
#include <vector>

#include "statmc/layers/atomic_file.h"
#include "statmc/layers/exr_files.h"
#include "tool.h"

int main(int argc, char* argv[])
{
    // Interrupted while writing, statmc leaves no temporary behind (the output keeps its
    // previous contents) and still ends as the signal says.
    statmc::layers::install_write_signal_handlers();
    statmc::layers::silence_library_debug_messages();
    const std::vector<std::string> args(argv + 1, argv + argc);
    return statmc::tool::run_tool(args, std::cout, std::cerr);
}
