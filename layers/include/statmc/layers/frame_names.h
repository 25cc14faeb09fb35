// The file names of a frame sequence as oiiotool spells them (OIIO's Filesystem rules):
// shot.#.exr = %04d, shot.@@@.exr = %03d, shot.%04d.exr, and frame lists such as 1-48x2.
// One place for the tool's sequences and statmc-render's --frames.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace statmc::layers {

/// The printf form of `text`'s frame pattern ("shot.%04d.exr" for shot.#.exr), or "" when
/// it has none. `range` receives a range written into the name (shot.1-10#.exr), if any.
std::string frame_pattern(const std::string& text, std::string* range = nullptr);

/// The file of `frame` under a printf pattern.
std::string frame_path(const std::string& pattern, int frame);

/// "1-48", "1-48x2", "3,5,10-20": the frames in order; nullopt when `list` is malformed
/// or names no frame.
std::optional<std::vector<int>> frame_list(const std::string& list);

}  // namespace statmc::layers
