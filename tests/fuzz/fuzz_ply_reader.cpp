// Bytes → statmc-render's PLY reader (ASCII and binary). A damaged mesh must end in an
// error naming the file; any other escape, crash or runaway allocation is a finding.
#include <cstdint>
#include <stdexcept>

#include "fuzz_input.h"
#include "statmc/render/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        statmc::render::read_ply(statmc::fuzz::as_file(data, size, ".ply"));
    } catch (const std::runtime_error&) {
    }
    return 0;
}
