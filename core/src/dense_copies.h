// Dense copies of strided planes: what a pass that reads a plane many times wants instead
// of an image's interleaved layers.
#pragma once

#include <vector>

#include "statmc/core/plane.h"

namespace statmc::detail {

/// Copies each of `planes` (all present, width × height) into `storage`, plane k at
/// k·width·height, and returns a dense view of each. One pass over the rows: planes that
/// interleave in an image share its pixel records, so each record is fetched once rather
/// than once per plane. Call inside the caller's thread limit.
std::vector<ConstPlane> dense_copies(const std::vector<ConstPlane>& planes, int width, int height,
                                     std::vector<float>& storage);

}  // namespace statmc::detail
