// A statmc command line (one argument per line) → the parser and every command's check,
// as statmc runs them before the first command. Nothing runs: no file is read or written.
// A bad line must be a HostError; any other escape or a crash is a finding.
#include <cstdint>

#include "fuzz_input.h"
#include "statmc/plugin_host/host_error.h"
#include "statmc/tool/command_line.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        statmc::tool::parse_program(statmc::fuzz::as_lines(data, size));
    } catch (const statmc::host::HostError&) {
    }
    return 0;
}
