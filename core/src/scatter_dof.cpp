#include "scatter_dof.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <boost/math/special_functions/trigamma.hpp>
#include <tbb/parallel_for.h>

namespace statmc::detail {

namespace {

// ln ψ'(x) on a uniform grid of ln x from x = 1e-4 to 1e7 (one trigamma per point, so the
// table costs well under a millisecond). ψ' falls monotonically, and ln ψ' against ln x
// bends slowly (its slope goes from −2 to −1), so linear interpolation between grid points
// is accurate to about 1e-5.
struct TrigammaTable {
    static constexpr int kSize = 4096;
    double lo = std::log(1e-4), step = (std::log(1e7) - std::log(1e-4)) / (kSize - 1);
    std::vector<double> log_y;  ///< decreasing

    TrigammaTable() : log_y(kSize)
    {
        for (int i = 0; i < kSize; ++i)
            log_y[i] = std::log(boost::math::trigamma(std::exp(lo + i * step)));
    }
};

const TrigammaTable& table()
{
    static const TrigammaTable t;
    return t;
}

}  // namespace

double inverse_trigamma(double y)
{
    const TrigammaTable& t = table();
    const double ly = std::log(y);
    if (ly >= t.log_y.front())
        return std::exp(t.lo);
    if (ly <= t.log_y.back())
        return std::exp(t.lo + (TrigammaTable::kSize - 1) * t.step);
    // The first grid point whose ln ψ' is at or below ln y, and the one before it.
    const auto after = std::lower_bound(t.log_y.begin(), t.log_y.end(), ly, std::greater<>());
    const int i = int(after - t.log_y.begin()) - 1;
    const double f = (t.log_y[i] - ly) / (t.log_y[i] - t.log_y[i + 1]);
    return std::exp(t.lo + (i + f) * t.step);
}

std::vector<float> log_variance_scatter(const VarianceLayout& L, int radius, double sigma)
{
    const int w = L.width, h = L.height, r = radius;
    const std::size_t n = L.pixels;
    std::vector<double> kernel(2 * r + 1);
    for (int d = -r; d <= r; ++d)
        kernel[d + r] = std::exp(-double(d) * d / (2 * sigma * sigma));
    std::vector<float> scatter(n * L.channels, 0.f);
    // Per pixel: its weight (1 where it counts), ln s² and (ln s²)², summed with the
    // Gaussian across each row; then down the columns.
    std::vector<double> rows(3 * n);
    for (int c = 0; c < L.channels; ++c) {
        const double* s2 = L.prior_s2.data() + c * n;
        tbb::parallel_for(0, h, [&](int y) {
            const std::size_t row = std::size_t(y) * w;
            std::vector<double> terms(3 * std::size_t(w));
            for (int x = 0; x < w; ++x) {
                const double v = s2[row + x];
                const bool counts = v > 0 && std::isfinite(v);
                const double l = counts ? std::log(v) : 0;
                terms[x] = counts ? 1 : 0;
                terms[w + x] = l;
                terms[2 * w + x] = l * l;
            }
            // Tap by tap across the row (the compiler vectorises across x); each pixel
            // still adds its taps from left to right.
            for (int k = 0; k < 3; ++k) {
                double* out = rows.data() + k * n + row;
                std::fill(out, out + w, 0.0);
                for (int d = -r; d <= r; ++d)
                    for (int x = std::max(0, -d); x < std::min(w, w - d); ++x)
                        out[x] += kernel[d + r] * terms[k * w + x + d];
            }
        });
        tbb::parallel_for(0, h, [&](int y) {
            std::vector<double> s(3 * std::size_t(w), 0.0);
            for (int yy = std::max(y - r, 0); yy <= std::min(y + r, h - 1); ++yy)
                for (int k = 0; k < 3; ++k) {
                    const double* in = rows.data() + k * n + std::size_t(yy) * w;
                    for (int x = 0; x < w; ++x)
                        s[k * w + x] += kernel[yy - y + r] * in[x];
                }
            for (int x = 0; x < w; ++x) {
                if (!(s[x] > 0))
                    continue;
                const double mean = s[w + x] / s[x];
                const double var = s[2 * w + x] / s[x] - mean * mean;
                if (var > 0)
                    scatter[c * n + std::size_t(y) * w + x] = float(var);
            }
        });
    }
    return scatter;
}

double scatter_dof(float scatter)
{
    return scatter > 0 ? 2 * inverse_trigamma(scatter) : std::numeric_limits<double>::infinity();
}

}  // namespace statmc::detail
