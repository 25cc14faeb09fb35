// Render checkpoints (docs/farm.md): the film's accumulators exactly as they are in memory,
// written atomically at a pass boundary, so that a render killed at any moment and resumed
// ends bitwise equal to one that never stopped. A text header names the render the film
// belongs to and carries CRC-32s of itself and of the payload; a checkpoint of another
// render, or a truncated or corrupted one, is refused with a message that says why.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include "statmc/render/film.h"

namespace statmc::render {

/// The render a checkpoint belongs to: resuming requires every field to match.
struct CheckpointIdentity {
    std::string scene;            ///< the scene file, as given
    std::uint32_t scene_crc = 0;  ///< SceneDescription::source_crc
    int seed = 0;
    int width = 0, height = 0;
    int task_index = 0, task_count = 1;
    int sample_begin = 0, sample_end = 0;  ///< the render's share of sample indices
    std::string settings;  ///< integrator settings and film layout, in words
};

/// Where a render has got to.
struct CheckpointProgress {
    std::uint64_t samples_done = 0;  ///< per pixel, counted from sample_begin
    double render_seconds = 0;       ///< time spent rendering them, over all runs
};

/// A checkpoint that cannot be used; the message names the file and what is wrong.
class CheckpointError : public std::runtime_error {
public:
    explicit CheckpointError(const std::string& message) : std::runtime_error(message) {}
};

/// Where the checkpoint of the render writing `output` lives: "out.exr" -> "out.exr.checkpoint".
std::string checkpoint_path(const std::string& output);

/// Writes `film` atomically (layers::write_file_atomically): on failure, a full disk
/// included, the previous checkpoint at `path` is kept and layers::FileError is thrown.
void write_checkpoint(const std::string& path, const Film& film, const CheckpointIdentity& identity,
                      const CheckpointProgress& progress);

/// Restores `film` (already sized for `expected`) from `path`. Throws CheckpointError when
/// the file is not a checkpoint, is truncated or corrupted, or belongs to another render
/// (naming the first field that differs: scene, seed, resolution, task, samples, settings).
CheckpointProgress read_checkpoint(const std::string& path, Film& film,
                                   const CheckpointIdentity& expected);

}  // namespace statmc::render
