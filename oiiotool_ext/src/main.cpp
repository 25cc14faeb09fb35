// statmc: the command-line host. Everything but argv handling lives in statmc_tool.
#include <iostream>
#include <string>
#include <vector>

#include "tool.h"

int main(int argc, char* argv[])
{
    const std::vector<std::string> args(argv + 1, argv + argc);
    return statmc::tool::run_tool(args, std::cout, std::cerr);
}
