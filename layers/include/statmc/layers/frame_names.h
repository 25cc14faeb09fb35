// The file names of a frame sequence as oiiotool spells them (OIIO's Filesystem rules):
// shot.#.exr = %04d, shot.@@@.exr = %03d, shot.%04d.exr, and frame lists such as 1-48x2.
// One place for the tool's sequences and statmc-render's --frames.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace statmc::layers {

/// The widest zero padding a frame pattern may ask for (shot.%032d.exr).
constexpr int kMaxFramePadding = 32;

/// The printf form of `text`'s frame pattern ("shot.%04d.exr" for shot.#.exr), or "" when
/// it has none. `range` receives a range written into the name (shot.1-10#.exr), if any.
/// Throws std::invalid_argument, naming `text`, for a padding over kMaxFramePadding.
std::string frame_pattern(const std::string& text, std::string* range = nullptr);

/// The file of `frame` under a printf pattern.
std::string frame_path(const std::string& pattern, int frame);

/// The most frame numbers the ranges of one frame list may span (steps included): 11½
/// hours at 24 fps, and a bound on the memory a list can ask for.
constexpr int kMaxFrames = 1'000'000;

/// "1-48", "1-48x2", "3,5,10-20": the frames in order; nullopt when `list` is malformed
/// (each item N, N-M, N-MxS or N-MyS; numbers of at most 9 digits), names no frame, or
/// spans more than kMaxFrames.
std::optional<std::vector<int>> frame_list(const std::string& list);

}  // namespace statmc::layers
