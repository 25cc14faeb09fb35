#include "statmc/core/variance_filter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "dense_copies.h"
#include "scatter_dof.h"
#include "statmc/core/critical_values.h"
#include "statmc/core/thread_limit.h"
#include "variance_filter_layout.h"

namespace statmc {

namespace {

void require_valid(const StatisticsView& view, TestDomain domain, const VarianceFilterOptions& o)
{
    if (!(o.radius >= 1 && o.radius <= 100))
        throw std::invalid_argument("variance filter: radius must be in [1, 100]");
    if (!(o.alpha > 0 && o.alpha < 1))
        throw std::invalid_argument("variance filter: alpha must be in (0, 1)");
    if (!(o.prior_dof >= 0 && std::isfinite(o.prior_dof)))
        throw std::invalid_argument("variance filter: prior_dof must be finite and >= 0");
    if (!(o.prior_alpha >= 0 && o.prior_alpha < 1))
        throw std::invalid_argument("variance filter: prior_alpha must be in [0, 1)");
    if (!(o.sigma_spatial > 0 && o.sigma_albedo > 0 && o.sigma_normal > 0))
        throw std::invalid_argument("variance filter: the sigmas must be > 0");
    if (domain == TestDomain::BoxCox && !(view.count && view.has_box_cox()))
        throw std::invalid_argument("variance filter: needs the Box-Cox statistics");
    if (domain == TestDomain::Untransformed && !(view.count && view.has_variance()))
        throw std::invalid_argument("variance filter: needs the variance");
}

// The mean and per-sample s² planes of one domain.
struct DomainPlanes {
    const std::array<ConstPlane, 4>& mean;
    const std::array<ConstPlane, 4>& variance;
    bool variance_of_mean;

    double s2(int c, int x, int y, double n) const
    {
        return double(variance[c](x, y)) * (variance_of_mean ? n : 1.0);
    }
};

DomainPlanes planes_of(const StatisticsView& view, TestDomain domain)
{
    if (domain == TestDomain::BoxCox)
        return {view.bc_mean, view.bc_variance, false};
    return {view.mean, view.variance, view.variance_of_mean};
}

// A pixel's own s² counts as an estimate (VarianceFilterOptions::alpha): enough values,
// and spread among them.
bool has_estimate(double n, double m2, double z) { return n >= 4 && n > z && m2 > 0; }

// Each pixel's estimate mark (0, or NaN where it has none), its s², whether the moderation
// may use it and, for the prior's test, its mean and s²/n: what the disk loop reads of a
// neighbour, made once per pixel rather than once per tap.
void fill_pixel_planes(const StatisticsView& view, const DomainPlanes& d, double z, bool moderate,
                       detail::VarianceLayout& L)
{
    const std::size_t n = L.pixels;
    const bool test_means = moderate && L.prior_z2 > 0;
    L.lend_s2.resize(n * view.channels);
    L.prior_s2.resize(n * view.channels);
    L.mean.resize(test_means ? n * view.channels : 0);
    L.mean_se2.resize(test_means ? n * view.channels : 0);
    tbb::parallel_for(0, view.height, [&](int y) {
        for (int c = 0; c < view.channels; ++c)
            for (int x = 0; x < view.width; ++x) {
                const double count = view.count(x, y);
                const double s2 = d.s2(c, x, y, count);
                const std::size_t k = c * n + std::size_t(y) * view.width + x;
                L.lend_s2[k] = has_estimate(count, s2 * (count - 1), z) ? s2 : NAN;
                L.prior_s2[k] = moderate && count >= 2 && std::isfinite(s2) ? s2 : NAN;
                if (test_means) {
                    L.mean[k] = d.mean[c](x, y);
                    L.mean_se2[k] = float(s2 / count);
                }
            }
    });
}

// The disk's offsets in raster order, the centre left out, with the spatial part of w_ij;
// the guides' part is exp(−Σ_groups f·|g_i − g_j|²) per guide present.
void fill_taps_and_guides(const StatisticsView& view, const Guides& guides,
                          const VarianceFilterOptions& o, detail::VarianceLayout& L)
{
    const int r = o.radius;
    const double falloff = 1.0 / (2.0 * double(o.sigma_spatial) * o.sigma_spatial);
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const int d2 = dx * dx + dy * dy;
            if (d2 <= r * r && d2 != 0)
                L.taps.push_back({dx, dy, std::exp(-double(d2) * falloff)});
        }
    std::vector<ConstPlane> planes;
    auto add_group = [&](const std::array<ConstPlane, 3>& g, float sigma) {
        L.guide_falloff[planes.size() / 3] = 1.0 / (2.0 * double(sigma) * sigma);
        planes.insert(planes.end(), g.begin(), g.end());
    };
    if (guides.has_albedo())
        add_group(guides.albedo, o.sigma_albedo);
    if (guides.has_normal())
        add_group(guides.normal, o.sigma_normal);
    for (const ConstPlane& copy :
         detail::dense_copies(planes, view.width, view.height, L.guide_storage))
        L.guide.push_back(copy.data);
}

// The centre's own terms: its s² with weight 1 where it is an estimate (or nothing), and
// in the moderation's sums where it is usable.
detail::VarianceSums own_terms(const detail::VarianceLayout& L, std::size_t p)
{
    detail::VarianceSums s;
    for (int c = 0; c < L.channels; ++c) {
        const std::size_t k = c * L.pixels + p;
        const bool has_estimate = !std::isnan(L.lend_s2[k]), usable = !std::isnan(L.prior_s2[k]);
        s.sum[c] = has_estimate ? L.lend_s2[k] : 0;
        s.weight[c] = has_estimate ? 1 : 0;
        s.prior_sum[c] = usable ? L.prior_s2[k] : 0;
        s.prior_weight[c] = usable ? 1 : 0;
    }
    return s;
}

// Whether neighbour j's mean is close enough to centre i's for j's s² to enter i's prior
// (VarianceFilterOptions::prior_alpha; always without that test). NaN fails.
bool in_prior(const detail::VarianceLayout& L, std::size_t i, std::size_t j)
{
    if (L.prior_z2 <= 0)
        return true;
    const double d = L.mean[i] - L.mean[j];
    return d * d <= L.prior_z2 * (L.mean_se2[i] + L.mean_se2[j]);
}

// Whether neighbour j's s² joins centre i's own sum: only for a borrower (no estimate of
// its own), from a neighbour that has one.
bool lends(const detail::VarianceLayout& L, std::size_t i, std::size_t j)
{
    return L.borrow && std::isnan(L.lend_s2[i]) && !std::isnan(L.lend_s2[j]);
}

// The scalar disk loop, and the reference the SIMD kernels match bit for bit: per channel
// the borrowed sum and the moderation's (centre first, then the disk in raster order: a
// fixed summation order, whichever thread runs the row).
void add_disk_scalar(const detail::VarianceLayout& L, int x, int y, detail::VarianceSums& s)
{
    const int w = L.width, h = L.height;
    const std::size_t n = L.pixels, p = std::size_t(y) * w + x;
    const bool interior = L.interior(x, y);
    for (const detail::VarianceTap& tap : L.taps) {
        const int xx = x + tap.dx, yy = y + tap.dy;
        if (!interior && (xx < 0 || xx >= w || yy < 0 || yy >= h))
            continue;
        const std::size_t q = std::size_t(yy) * w + xx;
        double wij = tap.spatial;
        if (L.guide_groups() > 0) {
            double exponent = 0;
            for (int group = 0; group < L.guide_groups(); ++group) {
                double d2 = 0;
                for (int k = 0; k < 3; ++k) {
                    const float* g = L.guide[3 * group + k];
                    const double d = double(g[p]) - g[q];
                    d2 = d2 + d * d;
                }
                exponent = exponent + d2 * L.guide_falloff[group];
            }
            wij = detail::guide_weight(tap.spatial, exponent);
        }
        for (int c = 0; c < L.channels; ++c) {
            const std::size_t i = c * n + p, j = c * n + q;
            if (lends(L, i, j)) {
                s.sum[c] += wij * L.lend_s2[j];
                s.weight[c] += wij;
            }
            if (!std::isnan(L.prior_s2[j]) && in_prior(L, i, j)) {
                s.prior_sum[c] += wij * L.prior_s2[j];
                s.prior_weight[c] += wij;
            }
        }
    }
}

detail::VarianceKernel kernel_at(SimdLevel level)
{
    switch (usable_simd_level(level)) {
    case SimdLevel::Avx512:
        return detail::variance_kernel_avx512();
    case SimdLevel::Avx2:
        return detail::variance_kernel_avx2();
    default:
        return {1, nullptr};
    }
}

}  // namespace

std::vector<float> denoise_variances(const StatisticsView& view, TestDomain domain,
                                     const Guides& guides, const VarianceFilterOptions& options,
                                     int nthreads, SimdLevel level, const PixelMask& wanted)
{
    require_valid(view, domain, options);
    require_mask_fits(wanted, view.width, view.height);
    const detail::VarianceKernel kernel = kernel_at(level);
    const DomainPlanes d = planes_of(view, domain);
    const double z = normal_critical_value(options.alpha);
    const bool moderate = options.prior_dof > 0;
    detail::VarianceLayout L;
    L.width = view.width;
    L.height = view.height;
    L.channels = view.channels;
    L.radius = options.radius;
    L.pixels = std::size_t(view.width) * view.height;
    // The prior's test on the means only exists with the moderation: without it the mean
    // planes are not filled, and the kernels must not read them.
    if (moderate && options.prior_alpha > 0) {
        const double z_prior = normal_critical_value(options.prior_alpha);
        L.prior_z2 = z_prior * z_prior;
    }
    L.borrow = options.borrow_without_interval;
    const std::size_t n = L.pixels;
    std::vector<float> out(n * L.channels);
    run_with_threads(nthreads, [&] {
        fill_taps_and_guides(view, guides, options, L);
        fill_pixel_planes(view, d, z, moderate, L);
        const std::vector<float> scatter =
            moderate && options.own_dof_from_scatter
                ? detail::log_variance_scatter(L, options.radius, options.sigma_spatial, wanted)
                : std::vector<float>();
        tbb::parallel_for(0, L.height, [&](int y) {
            // Unwanted pixels (PixelMask) are skipped, chunks of the kernel's width whole.
            const std::uint8_t* want =
                wanted.empty() ? nullptr : wanted.data() + std::size_t(y) * L.width;
            auto any_wanted = [&](int from, int to) {
                return !want ||
                       std::any_of(want + from, want + to, [](std::uint8_t v) { return v != 0; });
            };
            if (!any_wanted(0, L.width))
                return;
            std::vector<detail::VarianceSums> row(L.width);
            for (int x = 0; x < L.width; ++x)
                row[x] = own_terms(L, std::size_t(y) * L.width + x);
            // Chunks of interior pixels go to the SIMD kernel, the rest to the scalar loop;
            // both give the same bits, so the split cannot change the result.
            int x = 0;
            if (kernel.add_disk && L.interior(L.radius, y))
                for (x = L.radius; x + kernel.lanes <= L.width - L.radius; x += kernel.lanes)
                    if (any_wanted(x, x + kernel.lanes))
                        kernel.add_disk(L, x, y, &row[x]);
            for (int rest = 0; rest < L.width; ++rest)
                if ((rest < L.radius || rest >= x) && (!want || want[rest]))
                    add_disk_scalar(L, rest, y, row[rest]);
            for (int xx = 0; xx < L.width; ++xx) {
                if (want && !want[xx])
                    continue;
                const std::size_t p = std::size_t(y) * L.width + xx;
                const double count = view.count(xx, y);
                const detail::VarianceSums& s = row[xx];
                for (int c = 0; c < L.channels; ++c) {
                    const double own = d.s2(c, xx, y, count);
                    const double own_or_borrowed = s.weight[c] > 0 ? s.sum[c] / s.weight[c] : own;
                    if (!moderate || s.prior_weight[c] <= 0) {
                        out[c * n + p] = float(own_or_borrowed);
                        continue;
                    }
                    // Empirical Bayes (Smyth 2004): the neighbourhood's variance as a prior
                    // worth prior_dof degrees of freedom against the pixel's n − 1, or
                    // fewer where its s² is below the prior and its neighbourhood's ln s²
                    // scatters more than n − 1 allows.
                    const double prior = s.prior_sum[c] / s.prior_weight[c];
                    double dof = std::max(count - 1, 0.0);
                    if (!scatter.empty() && own_or_borrowed < prior)
                        dof = std::min(dof, detail::scatter_dof(scatter[c * n + p]));
                    out[c * n + p] =
                        dof > 0 && std::isfinite(own_or_borrowed)
                            ? float((options.prior_dof * prior + dof * own_or_borrowed) /
                                    (options.prior_dof + dof))
                            : float(prior);
                }
            }
        });
    });
    return out;
}

}  // namespace statmc
