// pbrt-v3 scene text → statmc-render's tokenizer and parser. Malformed text must end in a
// SceneError naming file:line (or a file error from a mesh or texture it names); any other
// escape, crash or runaway allocation is a finding.
#include <cstdint>
#include <stdexcept>

#include "fuzz_input.h"
#include "statmc/render/scene_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try {
        // Relative Include, mesh and texture names resolve against a directory with no
        // scene files, so they exercise the missing-file paths.
        statmc::render::parse_scene_string(statmc::fuzz::as_text(data, size), "fuzz.pbrt",
                                           "/nonexistent-statmc-fuzz");
    } catch (const statmc::render::SceneError&) {
    }
    return 0;
}
