#include "firefly_spread.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace statmc::detail {

namespace {

/// The kernel's weight of neighbour f in centre j's average (0 when the test fails): the
/// same formulas on the same padded planes. Fireflies are flagged only in the neighbour
/// thresholds, so both sides read the centre thresholds.
float filter_weight(const FilterLayout& L, std::ptrdiff_t j, std::ptrdiff_t f, int dx, int dy)
{
    for (int c = 0; c < L.channels; ++c) {
        const float d = L.mean[c][j] - L.mean[c][f];
        if (!(std::fma(d, d, -L.centre_threshold[c][f]) <= L.centre_threshold[c][j]))
            return 0.f;
    }
    if (L.guide_count == 0)
        return L.spatial(dx, dy);
    float arg = L.spatial_log(dx, dy);
    for (int g = 0; g < L.guide_count; ++g) {
        const float d = L.guide[g][j] - L.guide[g][f];
        arg = std::fma(-d, d, arg);
    }
    return std::exp(arg);
}

/// Fireflies by row, x ascending: a centre finds those in its disk without walking it.
struct FireflyRows {
    std::vector<std::vector<int>> x;           // per row
    std::vector<std::vector<std::size_t>> id;  // their positions in layout.fireflies

    explicit FireflyRows(const FilterLayout& L) : x(L.height), id(L.height)
    {
        for (std::size_t k = 0; k < L.fireflies.size(); ++k) {
            const std::size_t p = L.fireflies[k];
            x[p / L.width].push_back(int(p % L.width));
            id[p / L.width].push_back(k);
        }
    }

    /// Calls body(firefly index k, fx, fy, dx, dy) for the fireflies in the disk around
    /// (cx, cy), the centre itself excluded, in row-then-column order.
    template <class Body>
    void around(const FilterLayout& L, int cx, int cy, Body&& body) const
    {
        for (int dy = -L.pad_y; dy <= L.pad_y; ++dy) {
            const int y = cy + dy;
            if (y < 0 || y >= L.height || x[y].empty())
                continue;
            const int hw = L.half_width[dy + L.pad_y];
            const auto& row = x[y];
            for (auto it = std::lower_bound(row.begin(), row.end(), cx - hw);
                 it != row.end() && *it <= cx + hw; ++it)
                if (*it != cx || dy != 0)
                    body(id[y][it - row.begin()], *it, y, *it - cx, dy);
        }
    }
};

template <class Body>
void for_each_row(int height, Body&& body)
{
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            body(y);
    });
}

}  // namespace

void spread_fireflies(const FilterLayout& L, const std::vector<Plane>& out, Plane weight_sum, Plane members)
{
    const FireflyRows rows(L);
    auto at = [&](int x, int y) { return std::ptrdiff_t(y) * L.stride + x; };

    // W_j of the paper's filter: the kernel's sum plus the fireflies j accepts.
    std::vector<double> paper_sum(std::size_t(L.width) * L.height);
    for_each_row(L.height, [&](int y) {
        for (int x = 0; x < L.width; ++x) {
            double w = weight_sum(x, y);
            rows.around(L, x, y, [&](std::size_t, int fx, int fy, int dx, int dy) {
                w += filter_weight(L, at(x, y), at(fx, fy), dx, dy);
            });
            paper_sum[std::size_t(y) * L.width + x] = w;
        }
    });

    // s_f from the share c_f that the paper's filter hands out.
    std::vector<float> scale(L.fireflies.size());
    tbb::parallel_for(std::size_t(0), L.fireflies.size(), [&](std::size_t k) {
        const int fx = int(L.fireflies[k] % L.width), fy = int(L.fireflies[k] / L.width);
        double share = 1.0 / paper_sum[L.fireflies[k]];
        for (int dy = -L.pad_y; dy <= L.pad_y; ++dy) {
            const int y = fy + dy, hw = L.half_width[dy + L.pad_y];
            if (y < 0 || y >= L.height)
                continue;
            for (int dx = std::max(-hw, -fx); dx <= std::min(hw, L.width - 1 - fx); ++dx)
                if (dx || dy)
                    share += filter_weight(L, at(fx + dx, y), at(fx, fy), -dx, -dy) /
                             paper_sum[std::size_t(y) * L.width + fx + dx];
        }
        scale[k] = float(std::min(1.0, 1.0 / share));
    });

    // Each centre takes the fireflies it accepts, scaled.
    for_each_row(L.height, [&](int y) {
        for (int x = 0; x < L.width; ++x) {
            double add[4] = {}, w_add = 0;
            int count = 0;
            rows.around(L, x, y, [&](std::size_t k, int fx, int fy, int dx, int dy) {
                const double w = double(scale[k]) * filter_weight(L, at(x, y), at(fx, fy), dx, dy);
                if (!(w > 0))
                    return;
                for (int c = 0; c < L.channels; ++c)
                    add[c] += w * L.value[c][at(fx, fy)];
                w_add += w;
                ++count;
            });
            if (count == 0)
                continue;
            const double w0 = weight_sum(x, y);
            for (int c = 0; c < L.channels; ++c)
                out[c](x, y) = float((double(out[c](x, y)) * w0 + add[c]) / (w0 + w_add));
            weight_sum(x, y) = float(w0 + w_add);
            if (members)
                members(x, y) += float(count);
        }
    });
}

}  // namespace statmc::detail
