// method.md §5 written as plainly as possible, in double precision: the yardstick for
// the optimised filter in tests and benchmarks.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "statmc/core/critical_values.h"
#include "statmc/core/filter.h"
#include "statmc/core/firefly_guard.h"

namespace statmc {

namespace {

double squared_distance(const std::array<ConstPlane, 3>& guide, int xi, int yi, int xj, int yj)
{
    double d2 = 0;
    for (const ConstPlane& p : guide) {
        const double a = std::isfinite(p(xi, yi)) ? p(xi, yi) : 0.0;
        const double b = std::isfinite(p(xj, yj)) ? p(xj, yj) : 0.0;
        d2 += (a - b) * (a - b);
    }
    return d2;
}

}  // namespace

void filter_reference(const EstimatorImage& est, const Guides& guides,
                      const DenoiseOptions& options, const std::vector<Plane>& out,
                      const FilterDiagnostics& diagnostics)
{
    if (const std::string why = options.validate(); !why.empty())
        throw std::invalid_argument(why);
    if (int(out.size()) < est.channels)
        throw std::invalid_argument("fewer output planes than channels");
    const CriticalValues critical(options.alpha);
    const int r = options.radius;
    const std::vector<std::uint8_t> firefly = find_fireflies(est, options.firefly_ratio);
    auto gamma = [&](int x, int y) {
        return critical.gamma(2.0 * std::floor(est.count[est.index(0, x, y)]) - 2.0);
    };
    auto in_disk = [&](int xi, int yi, int xj, int yj) {
        const double p2 = double(xj - xi) * (xj - xi) + double(yj - yi) * (yj - yi);
        return xj >= 0 && yj >= 0 && xj < est.width && yj < est.height && p2 <= double(r) * r &&
               !(xj == xi && yj == yi);
    };
    // W_ij for testable i and j: the membership test times the spatial and guide terms.
    auto weight = [&](int xi, int yi, int xj, int yj) {
        const double gi = gamma(xi, yi), gj = gamma(xj, yj);
        for (int c = 0; c < est.channels; ++c) {
            const double d = double(est.test_mean[est.index(c, xi, yi)]) - est.test_mean[est.index(c, xj, yj)];
            const double bound = gi * gi * est.test_variance[est.index(c, xi, yi)] +
                                 gj * gj * est.test_variance[est.index(c, xj, yj)];
            if (!(d * d <= bound))
                return 0.0;
        }
        const double p2 = double(xj - xi) * (xj - xi) + double(yj - yi) * (yj - yi);
        double log_w = -p2 / (2.0 * double(options.sigma_spatial) * options.sigma_spatial);
        if (guides.has_albedo())
            log_w -= squared_distance(guides.albedo, xi, yi, xj, yj) /
                     (2.0 * double(options.sigma_albedo) * options.sigma_albedo);
        if (guides.has_normal())
            log_w -= squared_distance(guides.normal, xi, yi, xj, yj) /
                     (2.0 * double(options.sigma_normal) * options.sigma_normal);
        return std::exp(log_w);
    };

    const std::size_t pixels = est.pixels();
    std::vector<double> sum(pixels * est.channels), weight_sum(pixels, 1.0), members(pixels, 1.0);
    auto at = [&](int x, int y) { return std::size_t(y) * est.width + x; };
    for (int yi = 0; yi < est.height; ++yi)
        for (int xi = 0; xi < est.width; ++xi) {
            const std::size_t i = at(xi, yi);
            for (int c = 0; c < est.channels; ++c)
                sum[c * pixels + i] = est.value[est.index(c, xi, yi)];
            if (!est.testable(xi, yi))
                continue;
            for (int yj = yi - r; yj <= yi + r; ++yj)
                for (int xj = xi - r; xj <= xi + r; ++xj) {
                    if (!in_disk(xi, yi, xj, yj) || !est.testable(xj, yj) || firefly[at(xj, yj)])
                        continue;
                    const double w = weight(xi, yi, xj, yj);
                    if (w == 0)
                        continue;
                    for (int c = 0; c < est.channels; ++c)
                        sum[c * pixels + i] += w * est.value[est.index(c, xj, yj)];
                    weight_sum[i] += w;
                    members[i] += 1;
                }
        }
    // The firefly guard's second step (firefly_spread.h): each firefly joins the centres
    // that accept it, scaled so that it hands out at most its own value.
    auto for_each_firefly_near = [&](int xj, int yj, auto&& body) {
        for (int yf = yj - r; yf <= yj + r; ++yf)
            for (int xf = xj - r; xf <= xj + r; ++xf)
                if (in_disk(xj, yj, xf, yf) && firefly[at(xf, yf)])
                    body(xf, yf, weight(xj, yj, xf, yf));
    };
    std::vector<double> paper_sum = weight_sum;
    for (int yj = 0; yj < est.height; ++yj)
        for (int xj = 0; xj < est.width; ++xj)
            if (est.testable(xj, yj))
                for_each_firefly_near(xj, yj, [&](int, int, double w) { paper_sum[at(xj, yj)] += w; });
    std::vector<double> scale(pixels, 0.0);
    for (int yf = 0; yf < est.height; ++yf)
        for (int xf = 0; xf < est.width; ++xf) {
            if (!firefly[at(xf, yf)])
                continue;
            double share = 1.0 / paper_sum[at(xf, yf)];
            for (int yj = yf - r; yj <= yf + r; ++yj)
                for (int xj = xf - r; xj <= xf + r; ++xj)
                    if (in_disk(xf, yf, xj, yj) && est.testable(xj, yj))
                        share += weight(xj, yj, xf, yf) / paper_sum[at(xj, yj)];
            scale[at(xf, yf)] = std::min(1.0, 1.0 / share);
        }
    for (int yj = 0; yj < est.height; ++yj)
        for (int xj = 0; xj < est.width; ++xj) {
            if (!est.testable(xj, yj))
                continue;
            const std::size_t j = at(xj, yj);
            for_each_firefly_near(xj, yj, [&](int xf, int yf, double w) {
                w *= scale[at(xf, yf)];
                if (w == 0)
                    return;
                for (int c = 0; c < est.channels; ++c)
                    sum[c * pixels + j] += w * est.value[est.index(c, xf, yf)];
                weight_sum[j] += w;
                members[j] += 1;
            });
        }

    for (int y = 0; y < est.height; ++y)
        for (int x = 0; x < est.width; ++x) {
            const std::size_t i = at(x, y);
            for (int c = 0; c < est.channels; ++c)
                out[c](x, y) = float(sum[c * pixels + i] / weight_sum[i]);
            if (diagnostics.members)
                diagnostics.members(x, y) = float(members[i]);
            if (diagnostics.weight_sum)
                diagnostics.weight_sum(x, y) = float(weight_sum[i]);
        }
}

}  // namespace statmc
