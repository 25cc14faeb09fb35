// A frame split over farm tasks by sample index (docs/farm.md): task I of N draws sample
// indices [⌊I·S/N⌋, ⌊(I+1)·S/N⌋) of every pixel's stream, so the tasks together draw exactly
// the samples one render of S samples per pixel would, each once.
#pragma once

#include <string>

#include "statmc/layers/sample_provenance.h"

namespace statmc::render {

struct RenderTask {
    int index = 0, count = 1;
};

/// "I/N" with 0 <= I < N. Throws std::runtime_error naming `option` and what is wrong.
RenderTask parse_task(const std::string& text, const std::string& option = "--task");

/// Task `task`'s share of `total_spp`, never empty: throws std::runtime_error when there
/// are more tasks than samples per pixel.
layers::SampleRange task_samples(int total_spp, const RenderTask& task);

}  // namespace statmc::render
