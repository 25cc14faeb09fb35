#include "scatter_dof.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <boost/math/special_functions/trigamma.hpp>
#include <tbb/parallel_for.h>

namespace statmc::detail {

namespace {

// ln x against ln y = ln ψ'(x) on a uniform grid of ln y, for x from 1e-4 to 1e7, so that a
// lookup is one logarithm, one interpolation and one exponential. Built once from a finer
// forward table of ln ψ' on a uniform grid of ln x (one trigamma per point: well under a
// millisecond). ψ' falls monotonically, and ln x against ln ψ' bends slowly (its slope goes
// from −1/2 to −1), so linear interpolation is accurate to about 1e-5.
struct InverseTrigammaTable {
    static constexpr int kSize = 4096;
    double lo, step;            ///< the ln y grid: lo, lo + step, …
    std::vector<double> log_x;  ///< ln x at each point of it

    InverseTrigammaTable() : log_x(kSize)
    {
        constexpr int kForward = 8192;
        const double x_lo = std::log(1e-4), x_step = (std::log(1e7) - x_lo) / (kForward - 1);
        std::vector<double> log_y(kForward);  // decreasing
        for (int i = 0; i < kForward; ++i)
            log_y[i] = std::log(boost::math::trigamma(std::exp(x_lo + i * x_step)));
        lo = log_y.back();
        step = (log_y.front() - lo) / (kSize - 1);
        for (int k = 0; k < kSize; ++k) {
            const double ly = std::min(lo + k * step, log_y.front());
            // The first forward point at or below ly, and the one before it.
            const auto after = std::lower_bound(log_y.begin(), log_y.end(), ly, std::greater<>());
            const int i = std::max(int(after - log_y.begin()) - 1, 0);
            const int j = std::min(i + 1, kForward - 1);
            const double f = log_y[i] == log_y[j] ? 0 : (log_y[i] - ly) / (log_y[i] - log_y[j]);
            log_x[k] = x_lo + (i + f) * x_step;
        }
    }
};

const InverseTrigammaTable& table()
{
    static const InverseTrigammaTable t;
    return t;
}

}  // namespace

double inverse_trigamma(double y)
{
    const InverseTrigammaTable& t = table();
    const double u = (std::log(y) - t.lo) / t.step;
    if (!(u > 0))
        return std::exp(t.log_x.front());
    if (u >= InverseTrigammaTable::kSize - 1)
        return std::exp(t.log_x.back());
    const int i = int(u);
    const double f = u - i;
    return std::exp(t.log_x[i] + f * (t.log_x[i + 1] - t.log_x[i]));
}

namespace {

// out[x] = Σ_d kernel[d + r]·in[x + d] over the taps inside the row, each pixel's taps
// added from left to right (restrict: the compiler vectorises across x).
void add_taps(const double* __restrict in, double* __restrict out, int w,
              const std::vector<double>& kernel)
{
    const int r = int(kernel.size()) / 2;
    std::fill(out, out + w, 0.0);
    for (int d = -r; d <= r; ++d) {
        const double k = kernel[d + r];
        const int from = std::max(0, -d), to = std::min(w, w - d);
        for (int x = from; x < to; ++x)
            out[x] += k * in[x + d];
    }
}

// out[x] += k·in[x].
void add_scaled(const double* __restrict in, double* __restrict out, int w, double k)
{
    for (int x = 0; x < w; ++x)
        out[x] += k * in[x];
}

}  // namespace

std::vector<float> log_variance_scatter(const VarianceLayout& L, int radius, double sigma,
                                        const PixelMask& wanted)
{
    const int w = L.width, h = L.height, r = radius;
    // The rows that hold a wanted pixel, and the rows their squares read.
    std::vector<std::uint8_t> out_row(h, 1), in_row(h, 1);
    if (!wanted.empty())
        for (int y = 0; y < h; ++y) {
            const auto* m = wanted.data() + std::size_t(y) * w;
            out_row[y] = std::any_of(m, m + w, [](std::uint8_t v) { return v != 0; });
        }
    for (int y = 0; y < h; ++y)
        in_row[y] = std::any_of(out_row.begin() + std::max(y - r, 0),
                                out_row.begin() + std::min(y + r, h - 1) + 1,
                                [](std::uint8_t v) { return v != 0; });
    const std::size_t n = L.pixels;
    std::vector<double> kernel(2 * r + 1);
    for (int d = -r; d <= r; ++d)
        kernel[d + r] = std::exp(-double(d) * d / (2 * sigma * sigma));
    std::vector<float> scatter(n * L.channels, 0.f);
    // Per pixel: its weight (1 where it counts), ln s² and (ln s²)², summed with the
    // Gaussian across each row, then down the columns. A band of kChunk output rows at a
    // time, its rows' sums (and the r rows on either side) in a buffer that stays in cache.
    constexpr int kChunk = 32;
    const int chunks = (h + kChunk - 1) / kChunk;
    tbb::parallel_for(0, L.channels * chunks, [&](int task) {
        const int c = task / chunks, y0 = (task % chunks) * kChunk, y1 = std::min(h, y0 + kChunk);
        if (std::none_of(out_row.begin() + y0, out_row.begin() + y1,
                         [](std::uint8_t v) { return v != 0; }))
            return;
        const int ya = std::max(y0 - r, 0), yb = std::min(y1 + r, h);
        const double* s2 = L.prior_s2.data() + c * n;
        std::vector<double> terms(3 * std::size_t(w)), rows(3 * std::size_t(yb - ya) * w);
        auto band_row = [&](int k, int y) {
            return rows.data() + (std::size_t(k) * (yb - ya) + (y - ya)) * w;
        };
        for (int y = ya; y < yb; ++y) {
            if (!in_row[y])
                continue;
            const double* v = s2 + std::size_t(y) * w;
            for (int x = 0; x < w; ++x) {
                const bool counts = v[x] > 0 && std::isfinite(v[x]);
                const double l = counts ? std::log(v[x]) : 0;
                terms[x] = counts ? 1 : 0;
                terms[w + x] = l;
                terms[2 * w + x] = l * l;
            }
            // Tap by tap across the row (the compiler vectorises across x); each pixel
            // still adds its taps from left to right.
            for (int k = 0; k < 3; ++k)
                add_taps(terms.data() + std::size_t(k) * w, band_row(k, y), w, kernel);
        }
        std::vector<double> sums(3 * std::size_t(w));
        for (int y = y0; y < y1; ++y) {
            if (!out_row[y])
                continue;
            std::fill(sums.begin(), sums.end(), 0.0);
            for (int yy = std::max(y - r, 0); yy <= std::min(y + r, h - 1); ++yy)
                for (int k = 0; k < 3; ++k)
                    add_scaled(band_row(k, yy), sums.data() + std::size_t(k) * w, w,
                               kernel[yy - y + r]);
            for (int x = 0; x < w; ++x) {
                if (!(sums[x] > 0))
                    continue;
                const double mean = sums[w + x] / sums[x];
                const double var = sums[2 * w + x] / sums[x] - mean * mean;
                if (var > 0)
                    scatter[c * n + std::size_t(y) * w + x] = float(var);
            }
        }
    });
    return scatter;
}

double scatter_dof(float scatter)
{
    return scatter > 0 ? 2 * inverse_trigamma(scatter) : std::numeric_limits<double>::infinity();
}

}  // namespace statmc::detail
