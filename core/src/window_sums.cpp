#include "window_sums.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "statmc/core/critical_values.h"

namespace statmc::detail {

bool window_check_runs(const char* check, const StatisticsView& noisy,
                       const std::vector<Plane>& out, int radius, double alpha)
{
    const std::string name(check);
    if (radius < 0)
        throw std::invalid_argument(name + ": radius must be >= 0");
    if (!(alpha > 0 && alpha < 1))
        throw std::invalid_argument(name + ": alpha must be in (0, 1)");
    if (radius == 0)
        return false;
    if (!noisy.count || !noisy.has_variance())
        throw std::invalid_argument(name + ": needs the sample count and the variance");
    if (int(out.size()) < noisy.channels)
        throw std::invalid_argument(name + ": fewer output planes than channels");
    return true;
}

Windows windows_of(const StatisticsView& noisy, int radius, double alpha)
{
    Windows win;
    win.w = noisy.width;
    win.h = noisy.height;
    win.r = radius;
    win.pixels = std::size_t(win.w) * win.h;
    win.area = double(2 * radius + 1) * (2 * radius + 1);
    win.z = normal_critical_value(alpha);
    return win;
}

bool usable_mean(const StatisticsView& noisy, int c, int x, int y)
{
    return noisy.count(x, y) >= 2 && std::isfinite(noisy.mean[c](x, y));
}

double variance_of_mean(const StatisticsView& noisy, int c, int x, int y)
{
    const double s2 = noisy.variance[c](x, y);
    const double v = noisy.variance_of_mean ? s2 : s2 / noisy.count(x, y);
    return std::isfinite(v) && v > 0 ? v : 0.0;
}

void box_sums(const std::vector<double>& in, const Windows& win, std::vector<double>& column,
              std::vector<double>& out)
{
    const int w = win.w, h = win.h, r = win.r;
    tbb::parallel_for(0, h, [&](int y) {
        const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
        double* row = column.data() + std::size_t(y) * w;
        for (int x = 0; x < w; ++x)
            row[x] = 0;
        for (int yy = y0; yy <= y1; ++yy) {
            const double* src = in.data() + std::size_t(yy) * w;
            for (int x = 0; x < w; ++x)
                row[x] += src[x];
        }
    });
    tbb::parallel_for(0, h, [&](int y) {
        const double* row = column.data() + std::size_t(y) * w;
        double* dst = out.data() + std::size_t(y) * w;
        for (int x = 0; x < w; ++x) {
            const int x0 = std::max(0, x - r), x1 = std::min(w - 1, x + r);
            double s = 0;
            for (int xx = x0; xx <= x1; ++xx)
                s += row[xx];
            dst[x] = s;
        }
    });
}

}  // namespace statmc::detail
