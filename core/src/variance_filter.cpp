#include "statmc/core/variance_filter.h"

#include <array>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "statmc/core/thread_limit.h"
#include "statmc/core/variance_interval.h"

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
    if (!(o.sigma_spatial > 0 && o.sigma_albedo > 0 && o.sigma_normal > 0))
        throw std::invalid_argument("variance filter: the sigmas must be > 0");
    if (domain == TestDomain::BoxCox && !(view.count && view.has_box_cox_moment4()))
        throw std::invalid_argument(
            "variance filter: needs the Box-Cox statistics and their fourth moment (boxcoxM4)");
    if (domain == TestDomain::Untransformed && !(view.count && view.has_moments()))
        throw std::invalid_argument("variance filter: needs the variance and its moments M3, M4");
}

// The per-sample s² and M4/n planes of one domain.
struct DomainPlanes {
    const std::array<ConstPlane, 4>& variance;
    const std::array<ConstPlane, 4>& moment4;
    bool variance_of_mean;

    double s2(int c, int x, int y, double n) const
    {
        return double(variance[c](x, y)) * (variance_of_mean ? n : 1.0);
    }
};

DomainPlanes planes_of(const StatisticsView& view, TestDomain domain)
{
    if (domain == TestDomain::BoxCox)
        return {view.bc_variance, view.bc_moment4, false};
    return {view.variance, view.moment4, view.variance_of_mean};
}

// Each pixel's interval on ln σ², or a NaN centre where it has none.
struct LogIntervals {
    std::vector<float> centre, se2;  // channel-major
};

LogIntervals intervals_of(const StatisticsView& view, const DomainPlanes& d, double z)
{
    const std::size_t n = std::size_t(view.width) * view.height;
    LogIntervals out{std::vector<float>(n * view.channels), std::vector<float>(n * view.channels)};
    for (int c = 0; c < view.channels; ++c)
        for (int y = 0; y < view.height; ++y)
            for (int x = 0; x < view.width; ++x) {
                const double count = view.count(x, y);
                const double m2 = d.s2(c, x, y, count) * (count - 1);
                const double m4 = double(d.moment4[c](x, y)) * count;
                const auto interval = bonett_interval(count, m2, m4, z);
                const std::size_t k = c * n + std::size_t(y) * view.width + x;
                out.centre[k] = interval ? float(interval->centre) : NAN;
                const double se = interval ? interval->half_width / z : 0;
                out.se2[k] = float(se * se);
            }
    return out;
}

}  // namespace

std::vector<float> denoise_variances(const StatisticsView& view, TestDomain domain,
                                     const Guides& guides, const VarianceFilterOptions& options,
                                     int nthreads)
{
    require_valid(view, domain, options);
    const DomainPlanes d = planes_of(view, domain);
    const double z = normal_critical_value(options.alpha);
    const LogIntervals log = intervals_of(view, d, z);
    const int w = view.width, h = view.height, r = options.radius;
    const std::size_t n = std::size_t(w) * h;
    std::vector<float> out(n * view.channels);
    const double falloff = 1.0 / (2.0 * double(options.sigma_spatial) * options.sigma_spatial);
    const double albedo_falloff = 1.0 / (2.0 * double(options.sigma_albedo) * options.sigma_albedo);
    const double normal_falloff = 1.0 / (2.0 * double(options.sigma_normal) * options.sigma_normal);
    // The guides' part of w_ij: exp(−|g_i − g_j|²/(2σ²)) for each guide present.
    auto guide_weight = [&](int x, int y, int xx, int yy) {
        double exponent = 0;
        auto add = [&](const std::array<ConstPlane, 3>& g, double f) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) {
                const double d = double(g[k](x, y)) - g[k](xx, yy);
                d2 += d * d;
            }
            exponent += d2 * f;
        };
        if (guides.has_albedo())
            add(guides.albedo, albedo_falloff);
        if (guides.has_normal())
            add(guides.normal, normal_falloff);
        return exponent;
    };
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, h, [&](int y) {
            for (int c = 0; c < view.channels; ++c)
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = c * n + std::size_t(y) * w + x;
                    const double count = view.count(x, y);
                    const double own = d.s2(c, x, y, count);
                    const bool has_interval = !std::isnan(log.centre[i]);
                    const bool moderate = options.prior_dof > 0;
                    if (!has_interval && !options.borrow_without_interval && !moderate) {
                        out[i] = float(own);
                        continue;
                    }
                    // The centre first, then the disk in raster order: a fixed summation
                    // order, whichever thread runs the row. `prior` pools every neighbour
                    // with a variance, untested, for the moderation.
                    const bool own_usable = count >= 2 && std::isfinite(own);
                    double sum = has_interval ? own : 0, weight = has_interval ? 1 : 0;
                    double prior_sum = own_usable ? own : 0, prior_weight = own_usable ? 1 : 0;
                    for (int dy = -r; dy <= r; ++dy) {
                        const int yy = y + dy;
                        if (yy < 0 || yy >= h)
                            continue;
                        for (int dx = -r; dx <= r; ++dx) {
                            const int xx = x + dx, d2 = dx * dx + dy * dy;
                            if (xx < 0 || xx >= w || d2 > r * r || d2 == 0)
                                continue;
                            const std::size_t j = c * n + std::size_t(yy) * w + xx;
                            const double diff = double(log.centre[i]) - log.centre[j];
                            // NaN (no interval) fails the comparison: such a pixel joins none.
                            // A borrowing pixel (no interval) takes any that has one.
                            const bool member =
                                has_interval
                                    ? diff * diff <= z * z * (double(log.se2[i]) + log.se2[j])
                                    : options.borrow_without_interval && !std::isnan(log.centre[j]);
                            const double count_j = view.count(xx, yy);
                            const double s2_j = d.s2(c, xx, yy, count_j);
                            const bool usable = moderate && count_j >= 2 && std::isfinite(s2_j);
                            if (!member && !usable)
                                continue;
                            const double wij = std::exp(-d2 * falloff - guide_weight(x, y, xx, yy));
                            if (member) {
                                sum += wij * s2_j;
                                weight += wij;
                            }
                            if (usable) {
                                prior_sum += wij * s2_j;
                                prior_weight += wij;
                            }
                        }
                    }
                    const double tested = weight > 0 ? sum / weight : own;
                    if (!moderate || prior_weight <= 0) {
                        out[i] = float(tested);
                        continue;
                    }
                    const double prior = prior_sum / prior_weight;
                    const double dof = std::max(count - 1, 0.0);
                    out[i] = dof > 0 && std::isfinite(tested)
                                 ? float((options.prior_dof * prior + dof * tested) /
                                         (options.prior_dof + dof))
                                 : float(prior);
                }
        });
    });
    return out;
}

}  // namespace statmc
