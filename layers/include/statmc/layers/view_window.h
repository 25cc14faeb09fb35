// Sub-rectangles of core views. Core addresses a view from its own (0, 0), so a region
// of an image is the same planes with shifted origins: no copy.
#pragma once

#include <array>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc::layers {

/// The plane whose (0, 0) is (x0, y0) of `plane`; null stays null.
ConstPlane shifted(const ConstPlane& plane, int x0, int y0);
Plane shifted(const Plane& plane, int x0, int y0);
std::array<ConstPlane, 3> shifted(const std::array<ConstPlane, 3>& planes, int x0, int y0);

/// The width × height window of `view` whose corner is (x0, y0) of `view`. The caller
/// keeps the window inside the view.
StatisticsView view_window(const StatisticsView& view, int x0, int y0, int width, int height);

}  // namespace statmc::layers
