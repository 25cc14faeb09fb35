#include "statmc/layers/view_window.h"

namespace statmc::layers {

ConstPlane shifted(const ConstPlane& plane, int x0, int y0)
{
    if (!plane)
        return plane;
    return {plane.data + x0 * plane.xstride + y0 * plane.ystride, plane.xstride, plane.ystride};
}

Plane shifted(const Plane& plane, int x0, int y0)
{
    if (!plane)
        return plane;
    return {plane.data + x0 * plane.xstride + y0 * plane.ystride, plane.xstride, plane.ystride};
}

std::array<ConstPlane, 3> shifted(const std::array<ConstPlane, 3>& planes, int x0, int y0)
{
    return {shifted(planes[0], x0, y0), shifted(planes[1], x0, y0), shifted(planes[2], x0, y0)};
}

StatisticsView view_window(const StatisticsView& view, int x0, int y0, int width, int height)
{
    StatisticsView w = view;
    w.width = width;
    w.height = height;
    w.count = shifted(view.count, x0, y0);
    for (int c = 0; c < 4; ++c) {
        w.mean[c] = shifted(view.mean[c], x0, y0);
        w.variance[c] = shifted(view.variance[c], x0, y0);
        w.bc_mean[c] = shifted(view.bc_mean[c], x0, y0);
        w.bc_variance[c] = shifted(view.bc_variance[c], x0, y0);
        w.bc_moment3[c] = shifted(view.bc_moment3[c], x0, y0);
        w.moment3[c] = shifted(view.moment3[c], x0, y0);
        w.moment4[c] = shifted(view.moment4[c], x0, y0);
        w.bc_moment4[c] = shifted(view.bc_moment4[c], x0, y0);
    }
    return w;
}

}  // namespace statmc::layers
