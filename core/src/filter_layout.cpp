#include "filter_layout.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "statmc/core/critical_values.h"

namespace statmc::detail {

namespace {

constexpr float kNever = -std::numeric_limits<float>::infinity();

float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.f; }

void build_window(FilterLayout& L, const DenoiseOptions& options)
{
    const int r = options.radius;
    const double r2 = double(r) * r;
    const double inv_two_sigma2 = 1.0 / (2.0 * double(options.sigma_spatial) * options.sigma_spatial);
    const int cols = 2 * L.pad_x + 1;
    L.half_width.resize(2 * L.pad_y + 1);
    L.spatial_weight.assign(std::size_t(cols) * (2 * L.pad_y + 1), 0.f);
    L.spatial_log_weight.assign(L.spatial_weight.size(), kNever);
    for (int dy = -L.pad_y; dy <= L.pad_y; ++dy) {
        const int hw = int(std::floor(std::sqrt(std::max(0.0, r2 - double(dy) * dy))));
        L.half_width[dy + L.pad_y] = std::min(hw, L.pad_x);
        for (int dx = -L.half_width[dy + L.pad_y]; dx <= L.half_width[dy + L.pad_y]; ++dx) {
            const double log_w = -(double(dx) * dx + double(dy) * dy) * inv_two_sigma2;
            L.spatial_log_weight[L.table_index(dx, dy)] = float(log_w);
            L.spatial_weight[L.table_index(dx, dy)] = float(std::exp(log_w));
        }
    }
}

}  // namespace

FilterLayout make_filter_layout(const EstimatorImage& est, const Guides& guides,
                                const DenoiseOptions& options, int nthreads,
                                bool with_inverse_count)
{
    FilterLayout L;
    L.width = est.width;
    L.height = est.height;
    L.channels = est.channels;
    // No neighbour lies further than the image extends; clamping keeps padding small
    // for a radius larger than the image.
    L.pad_x = std::min(options.radius, est.width - 1);
    L.pad_y = std::min(options.radius, est.height - 1);
    // Room for the last SIMD chunk of a row to read past the width.
    constexpr int kMaxLanes = 8;
    const int padded_width = est.width + 2 * L.pad_x + kMaxLanes;
    L.stride = padded_width;
    L.plane_size = std::size_t(padded_width) * (est.height + 2 * L.pad_y);

    std::vector<std::pair<ConstPlane, float>> guide_planes;  // plane, 1/(√2·σ)
    if (guides.has_albedo())
        for (const ConstPlane& p : guides.albedo)
            guide_planes.emplace_back(p, float(1.0 / (std::sqrt(2.0) * options.sigma_albedo)));
    if (guides.has_normal())
        for (const ConstPlane& p : guides.normal)
            guide_planes.emplace_back(p, float(1.0 / (std::sqrt(2.0) * options.sigma_normal)));
    L.guide_count = int(guide_planes.size());

    const int planes = 3 * L.channels + L.guide_count + (with_inverse_count ? 1 : 0);
    L.storage.assign(L.plane_size * planes, 0.f);
    const std::ptrdiff_t origin = std::ptrdiff_t(L.pad_y) * L.stride + L.pad_x;
    auto plane_origin = [&](int k) { return L.storage.data() + k * L.plane_size + origin; };
    float* mean[4];
    float* threshold[4];
    float* value[4];
    for (int c = 0; c < L.channels; ++c) {
        mean[c] = plane_origin(c);
        threshold[c] = plane_origin(L.channels + c);
        value[c] = plane_origin(2 * L.channels + c);
        std::fill(threshold[c] - origin, threshold[c] - origin + L.plane_size, kNever);
        L.mean[c] = mean[c];
        L.threshold[c] = threshold[c];
        L.value[c] = value[c];
    }
    float* guide[6];
    for (int g = 0; g < L.guide_count; ++g) {
        guide[g] = plane_origin(3 * L.channels + g);
        L.guide[g] = guide[g];
    }
    float* inverse_count =
        with_inverse_count ? plane_origin(3 * L.channels + L.guide_count) : nullptr;
    L.inverse_count = inverse_count;

    float max_count = 0;
    for (std::size_t i = 0; i < est.pixels(); ++i)
        max_count = std::max(max_count, std::isfinite(est.count[i]) ? est.count[i] : 0.f);
    const auto table = CriticalValues::shared(options.alpha, 2.0 * std::floor(max_count) - 2.0);
    const CriticalValues& critical = *table;
    auto fill_rows = [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y)
            for (int x = 0; x < est.width; ++x) {
                const std::ptrdiff_t p = std::ptrdiff_t(y) * L.stride + x;
                const bool testable = est.testable(x, y);
                // The fast form tests each side at df = 2n − 2 (method.md §4).
                const double gamma =
                    testable ? critical.gamma(2.0 * std::floor(est.count[est.index(0, x, y)]) - 2.0) : 0.0;
                for (int c = 0; c < L.channels; ++c) {
                    const std::size_t i = est.index(c, x, y);
                    value[c][p] = est.value[i];
                    mean[c][p] = testable ? est.test_mean[i] : 0.f;
                    threshold[c][p] = testable
                        ? float(std::min(gamma * gamma * est.test_variance[i], double(FLT_MAX)))
                        : kNever;
                }
                for (int g = 0; g < L.guide_count; ++g)
                    guide[g][p] = finite_or_zero(guide_planes[g].first(x, y)) * guide_planes[g].second;
                if (inverse_count) {
                    const float n = finite_or_zero(est.count[est.index(0, x, y)]);
                    inverse_count[p] = n > 0 ? 1.f / n : 0.f;
                }
            }
    };
    if (nthreads == 1)
        fill_rows(tbb::blocked_range<int>(0, est.height));
    else
        tbb::parallel_for(tbb::blocked_range<int>(0, est.height, 16), fill_rows);

    build_window(L, options);
    return L;
}

}  // namespace statmc::detail
