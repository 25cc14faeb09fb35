#include "window_sums.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "dense_copies.h"
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

StatisticsView dense_check_inputs(const StatisticsView& noisy, std::vector<float>& storage)
{
    const int w = noisy.width, h = noisy.height;
    StatisticsView dense;
    dense.width = w;
    dense.height = h;
    dense.channels = noisy.channels;
    dense.variance_of_mean = noisy.variance_of_mean;
    // The planes the view has (a missing one stays missing, for the checks to refuse).
    std::vector<ConstPlane> from;
    std::vector<ConstPlane*> to;
    auto add = [&](const ConstPlane& plane, ConstPlane& copy) {
        if (plane) {
            from.push_back(plane);
            to.push_back(&copy);
        }
    };
    add(noisy.count, dense.count);
    for (int c = 0; c < noisy.channels; ++c) {
        add(noisy.mean[c], dense.mean[c]);
        add(noisy.variance[c], dense.variance[c]);
    }
    const std::vector<ConstPlane> copies = dense_copies(from, w, h, storage);
    for (std::size_t k = 0; k < copies.size(); ++k)
        *to[k] = copies[k];
    return dense;
}

void box_sums(const std::vector<double>& in, const Windows& win, std::vector<double>& column,
              std::vector<double>& out)
{
    const int w = win.w, h = win.h, r = win.r;
    // Each pass sums kBlock neighbouring pixels side by side, in registers, rather than
    // each pixel as a chain of dependent adds; every pixel's terms keep their order.
    constexpr int kBlock = 8;
    // Down the columns.
    tbb::parallel_for(0, h, [&](int y) {
        const int y0 = std::max(0, y - r), y1 = std::min(h - 1, y + r);
        double* row = column.data() + std::size_t(y) * w;
        const double* top = in.data() + std::size_t(y0) * w;
        int x = 0;
        for (; x + kBlock <= w; x += kBlock) {
            double s[kBlock] = {};
            for (int yy = 0; yy <= y1 - y0; ++yy)
                for (int j = 0; j < kBlock; ++j)
                    s[j] += top[std::size_t(yy) * w + x + j];
            for (int j = 0; j < kBlock; ++j)
                row[x + j] = s[j];
        }
        for (; x < w; ++x) {
            double s = 0;
            for (int yy = 0; yy <= y1 - y0; ++yy)
                s += top[std::size_t(yy) * w + x];
            row[x] = s;
        }
    });
    // Across the rows; pixels whose window the image clips, one at a time.
    const int lo = std::min(r, w), hi = std::max(lo, w - r);  // [lo, hi): full windows
    tbb::parallel_for(0, h, [&](int y) {
        const double* row = column.data() + std::size_t(y) * w;
        double* dst = out.data() + std::size_t(y) * w;
        auto clipped = [&](int x) {
            const int x0 = std::max(0, x - r), x1 = std::min(w - 1, x + r);
            double s = 0;
            for (int xx = x0; xx <= x1; ++xx)
                s += row[xx];
            dst[x] = s;
        };
        for (int x = 0; x < lo; ++x)
            clipped(x);
        int x = lo;
        for (; x + kBlock <= hi; x += kBlock) {
            double s[kBlock] = {};
            for (int k = -r; k <= r; ++k)
                for (int j = 0; j < kBlock; ++j)
                    s[j] += row[x + j + k];
            for (int j = 0; j < kBlock; ++j)
                dst[x + j] = s[j];
        }
        for (; x < w; ++x)
            clipped(x);
    });
}

}  // namespace statmc::detail
