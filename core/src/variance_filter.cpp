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
    tbb::parallel_for(0, view.height, [&](int y) {
        for (int c = 0; c < view.channels; ++c)
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
    });
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
    const int w = view.width, h = view.height, r = options.radius;
    const int channels = view.channels;
    const std::size_t n = std::size_t(w) * h;
    std::vector<float> out(n * channels);
    LogIntervals log;
    run_with_threads(nthreads, [&] { log = intervals_of(view, d, z); });
    // What the disk loop reads of a neighbour, made once per pixel rather than once per tap:
    // its s² and whether the moderation may use it.
    std::vector<double> s2(n * channels);
    std::vector<char> usable(n * channels);
    const bool moderate = options.prior_dof > 0;
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, h, [&](int y) {
            for (int c = 0; c < channels; ++c)
                for (int x = 0; x < w; ++x) {
                    const double count = view.count(x, y);
                    const std::size_t k = c * n + std::size_t(y) * w + x;
                    s2[k] = d.s2(c, x, y, count);
                    usable[k] = moderate && count >= 2 && std::isfinite(s2[k]);
                }
        });
    });
    // The disk's offsets in raster order, the centre left out, with the spatial part of w_ij;
    // the guides' part is exp(−|g_i − g_j|²/(2σ²)) per guide present. Each pair's weight is
    // computed once for all channels.
    struct Tap {
        int dx, dy;
        double spatial;
    };
    std::vector<Tap> taps;
    const double falloff = 1.0 / (2.0 * double(options.sigma_spatial) * options.sigma_spatial);
    for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
            const int d2 = dx * dx + dy * dy;
            if (d2 <= r * r && d2 != 0)
                taps.push_back({dx, dy, std::exp(-double(d2) * falloff)});
        }
    const double albedo_falloff = 1.0 / (2.0 * double(options.sigma_albedo) * options.sigma_albedo);
    const double normal_falloff = 1.0 / (2.0 * double(options.sigma_normal) * options.sigma_normal);
    const bool guided = guides.has_albedo() || guides.has_normal();
    auto guide_exponent = [&](int x, int y, int xx, int yy) {
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
    const double z2 = z * z;
    constexpr int kMaxChannels = 4;
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t p = std::size_t(y) * w + x;
                const double count = view.count(x, y);
                // Per channel: the tested sum (centre first, then the disk in raster order:
                // a fixed summation order, whichever thread runs the row) and, for the
                // moderation, the untested one over every neighbour with a variance.
                double own[kMaxChannels], sum[kMaxChannels], weight[kMaxChannels];
                double prior_sum[kMaxChannels], prior_weight[kMaxChannels];
                bool has_interval[kMaxChannels], active = moderate;
                for (int c = 0; c < channels; ++c) {
                    own[c] = s2[c * n + p];
                    has_interval[c] = !std::isnan(log.centre[c * n + p]);
                    active |= has_interval[c] || options.borrow_without_interval;
                    sum[c] = has_interval[c] ? own[c] : 0;
                    weight[c] = has_interval[c] ? 1 : 0;
                    const bool own_usable = count >= 2 && std::isfinite(own[c]);
                    prior_sum[c] = own_usable ? own[c] : 0;
                    prior_weight[c] = own_usable ? 1 : 0;
                }
                const bool interior = x >= r && x < w - r && y >= r && y < h - r;
                for (std::size_t t = 0; active && t < taps.size(); ++t) {
                    const int xx = x + taps[t].dx, yy = y + taps[t].dy;
                    if (!interior && (xx < 0 || xx >= w || yy < 0 || yy >= h))
                        continue;
                    const std::size_t q = std::size_t(yy) * w + xx;
                    double wij = -1;  // computed on first use
                    for (int c = 0; c < channels; ++c) {
                        const std::size_t i = c * n + p, j = c * n + q;
                        // NaN (no interval) fails the comparison: such a pixel joins none.
                        // A borrowing pixel (no interval) takes any that has one.
                        const double diff = double(log.centre[i]) - log.centre[j];
                        const bool member =
                            has_interval[c]
                                ? diff * diff <= z2 * (double(log.se2[i]) + log.se2[j])
                                : options.borrow_without_interval && !std::isnan(log.centre[j]);
                        if (!member && !usable[j])
                            continue;
                        if (wij < 0)
                            wij = taps[t].spatial *
                                  (guided ? std::exp(-guide_exponent(x, y, xx, yy)) : 1.0);
                        if (member) {
                            sum[c] += wij * s2[j];
                            weight[c] += wij;
                        }
                        if (usable[j]) {
                            prior_sum[c] += wij * s2[j];
                            prior_weight[c] += wij;
                        }
                    }
                }
                for (int c = 0; c < channels; ++c) {
                    const double tested = weight[c] > 0 ? sum[c] / weight[c] : own[c];
                    if (!moderate || prior_weight[c] <= 0) {
                        out[c * n + p] = float(tested);
                        continue;
                    }
                    // Empirical Bayes (Smyth 2004): the neighbourhood's variance as a prior
                    // worth prior_dof degrees of freedom against the pixel's n − 1.
                    const double prior = prior_sum[c] / prior_weight[c];
                    const double dof = std::max(count - 1, 0.0);
                    out[c * n + p] = dof > 0 && std::isfinite(tested)
                                         ? float((options.prior_dof * prior + dof * tested) /
                                                 (options.prior_dof + dof))
                                         : float(prior);
                }
            }
        });
    });
    return out;
}

}  // namespace statmc
