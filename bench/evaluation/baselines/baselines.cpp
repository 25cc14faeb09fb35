#include "baselines.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace statmc::baselines {

namespace {

template <class Body>
void for_each_row(int h, Body&& body)
{
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& r) {
        for (int y = r.begin(); y < r.end(); ++y)
            body(y);
    });
}

/// Box sum over [x − f, x + f] × [y − f, y + f] ∩ image of a dense w × h plane. Running
/// sums in double: terms span many decades, and a float sum that adds then subtracts a
/// large one loses the small ones beside it.
void box_sum(const std::vector<float>& in, std::vector<float>& out, std::vector<double>& tmp, int w,
             int h, int f)
{
    for_each_row(h, [&](int y) {
        const float* row = in.data() + std::size_t(y) * w;
        double* t = tmp.data() + std::size_t(y) * w;
        double s = 0;
        for (int x = 0; x <= std::min(f, w - 1); ++x)
            s += row[x];
        for (int x = 0; x < w; ++x) {
            t[x] = s;
            if (x + f + 1 < w)
                s += row[x + f + 1];
            if (x - f >= 0)
                s -= row[x - f];
        }
    });
    tbb::parallel_for(tbb::blocked_range<int>(0, w, 64), [&](const tbb::blocked_range<int>& cols) {
        for (int x = cols.begin(); x < cols.end(); ++x) {
            double s = 0;
            for (int y = 0; y <= std::min(f, h - 1); ++y)
                s += tmp[std::size_t(y) * w + x];
            for (int y = 0; y < h; ++y) {
                out[std::size_t(y) * w + x] = float(s);
                if (y + f + 1 < h)
                    s += tmp[std::size_t(y + f + 1) * w + x];
                if (y - f >= 0)
                    s -= tmp[std::size_t(y - f) * w + x];
            }
        }
    });
}

/// How many of [i − f, i + f] ∩ [0, n) stay in [0, n) when shifted by d: the in-image
/// pixels, along one axis, of the patch around i for the offset d.
int patch_overlap(int i, int f, int n, int d)
{
    const int lo = std::max({i - f, 0, -d}), hi = std::min({i + f, n - 1, n - 1 - d});
    return std::max(0, hi - lo + 1);
}

}  // namespace

void nlm(const std::array<ConstPlane, 3>& mean, const std::array<ConstPlane, 3>& variance, int w,
         int h, const NlmOptions& o, const std::array<Plane, 3>& out)
{
    constexpr float kEpsilon = 1e-10f;
    const std::size_t n = std::size_t(w) * h;
    // A term this large already gives the patch a weight of 0; larger ones only cost precision.
    constexpr float kFar = 1e4f;
    std::vector<float> distance(n), distance_sum(n);
    std::vector<int> overlap_x(std::size_t(w), 0);
    std::vector<double> tmp(n);
    std::vector<double> acc(3 * n, 0.0), weight_sum(n, 0.0);
    for (int dy = -o.search_radius; dy <= o.search_radius; ++dy)
        for (int dx = -o.search_radius; dx <= o.search_radius; ++dx) {
            // Per-pixel distance terms of the pair (p, p + d), then their patch means.
            for_each_row(h, [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const int qx = x + dx, qy = y + dy;
                    const std::size_t i = std::size_t(y) * w + x;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h) {
                        distance[i] = 0;
                        continue;
                    }
                    float d = 0;
                    for (int c = 0; c < 3; ++c) {
                        const float vp = std::max(0.f, variance[c](x, y)),
                                    vq = std::max(0.f, variance[c](qx, qy));
                        const float diff = mean[c](x, y) - mean[c](qx, qy);
                        d += (diff * diff - o.alpha * (vp + std::min(vp, vq))) /
                             (kEpsilon + o.k * o.k * (vp + vq));
                    }
                    distance[i] = std::isfinite(d) ? std::min(d / 3, kFar) : kFar;
                }
            });
            box_sum(distance, distance_sum, tmp, w, h, o.patch_radius);
            // The patch's pixel pairs with both ends in the image: a product of two overlaps.
            for (int x = 0; x < w; ++x)
                overlap_x[std::size_t(x)] = patch_overlap(x, o.patch_radius, w, dx);
            for_each_row(h, [&](int y) {
                const int overlap_y = patch_overlap(y, o.patch_radius, h, dy);
                for (int x = 0; x < w; ++x) {
                    const int qx = x + dx, qy = y + dy;
                    const std::size_t i = std::size_t(y) * w + x;
                    const int valid = overlap_x[std::size_t(x)] * overlap_y;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h || valid <= 0)
                        continue;
                    const double wgt = std::exp(-std::max(0.0, double(distance_sum[i]) / valid));
                    for (int c = 0; c < 3; ++c)
                        acc[c * n + i] += wgt * mean[c](qx, qy);
                    weight_sum[i] += wgt;
                }
            });
        }
    for_each_row(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y) * w + x;
            for (int c = 0; c < 3; ++c)
                out[c](x, y) =
                    weight_sum[i] > 0 ? float(acc[c * n + i] / weight_sum[i]) : mean[c](x, y);
        }
    });
}

void cross_bilateral(const std::array<ConstPlane, 3>& mean, const Guides& guides, int w, int h,
                     const CrossBilateralOptions& o, const std::array<Plane, 3>& out)
{
    const double inv_s = 1.0 / (2.0 * o.sigma_spatial * o.sigma_spatial);
    const double inv_a = 1.0 / (2.0 * o.sigma_albedo * o.sigma_albedo);
    const double inv_n = 1.0 / (2.0 * o.sigma_normal * o.sigma_normal);
    auto feature_distance = [](const std::array<ConstPlane, 3>& g, int x, int y, int u, int v) {
        double d = 0;
        for (const ConstPlane& p : g) {
            const double a = std::isfinite(p(x, y)) ? p(x, y) : 0.0,
                         b = std::isfinite(p(u, v)) ? p(u, v) : 0.0;
            d += (a - b) * (a - b);
        }
        return d;
    };
    for_each_row(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            double acc[3] = {}, weight_sum = 0;
            for (int v = std::max(0, y - o.radius); v <= std::min(h - 1, y + o.radius); ++v)
                for (int u = std::max(0, x - o.radius); u <= std::min(w - 1, x + o.radius); ++u) {
                    double log_w = -(double(u - x) * (u - x) + double(v - y) * (v - y)) * inv_s;
                    if (guides.has_albedo())
                        log_w -= feature_distance(guides.albedo, x, y, u, v) * inv_a;
                    if (guides.has_normal())
                        log_w -= feature_distance(guides.normal, x, y, u, v) * inv_n;
                    const double wgt = std::exp(log_w);
                    for (int c = 0; c < 3; ++c)
                        acc[c] += wgt * mean[c](u, v);
                    weight_sum += wgt;
                }
            for (int c = 0; c < 3; ++c)
                out[c](x, y) = float(acc[c] / weight_sum);
        }
    });
}

}  // namespace statmc::baselines
