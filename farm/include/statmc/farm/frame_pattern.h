// Frame numbers in file names: printf patterns such as "shot.%04d.pbrt" and ranges such as
// "1-24", as the farm front end takes them (docs/farm.md).
#pragma once

#include <string>
#include <vector>

namespace statmc::farm {

/// Whether `pattern` holds one frame-number conversion (%d, %4d or %04d).
bool has_frame_number(const std::string& pattern);

/// `pattern` with its one frame-number conversion replaced by `frame`; "%%" is a percent
/// sign. Throws std::runtime_error naming the pattern when it holds any other conversion
/// or more than one.
std::string expand_frame(const std::string& pattern, int frame);

/// "A-B" (A <= B) or "A": the frames A, A+1, ..., B. Throws std::runtime_error otherwise.
std::vector<int> parse_frames(const std::string& text);

}  // namespace statmc::farm
