// docs/method.md §5 written as plainly as possible, in double precision: the yardstick for
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

// A guide's variance of the mean at a pixel: s²/n, 0 where either is not positive finite.
double variance_of_mean(const ConstPlane& variance, const EstimatorImage& est, int x, int y)
{
    if (!variance)  // absent, or the correction is off (guide_exponent)
        return 0.0;
    const double v = variance(x, y), n = est.count[est.index(0, x, y)];
    return v > 0 && std::isfinite(v) && n > 0 && std::isfinite(n) ? v / n : 0.0;
}

// The guides' part of −log w: D − 2·min(U_i, U_j), at least 0, with
// D = Σ_guides |g_i − g_j|²/(2σ²) and U = Σ_guides (s²/n)/(2σ²): the distance less what
// the guides' own noise explains, the less noisy side's twice, so that i weighs j as j
// weighs i (docs/method.md §5).
double guide_exponent(const EstimatorImage& est, const Guides& guides,
                      const DenoiseOptions& options, int xi, int yi, int xj, int yj)
{
    double e = 0, noise_i = 0, noise_j = 0;
    auto add = [&](const std::array<ConstPlane, 3>& g, ConstPlane variance, float sigma) {
        const double falloff = 1.0 / (2.0 * double(sigma) * sigma);
        if (!options.guide_noise)
            variance = {};
        e += squared_distance(g, xi, yi, xj, yj) * falloff;
        noise_i += variance_of_mean(variance, est, xi, yi) * falloff;
        noise_j += variance_of_mean(variance, est, xj, yj) * falloff;
    };
    if (guides.has_albedo())
        add(guides.albedo, guides.albedo_variance, options.sigma_albedo);
    if (guides.has_normal())
        add(guides.normal, guides.normal_variance, options.sigma_normal);
    return std::max(0.0, e - 2 * std::min(noise_i, noise_j));
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
    const NoiseLevels noise = noise_levels(est, options.firefly_ratio);
    auto pixel = [&](int x, int y) { return std::size_t(y) * est.width + x; };
    auto gamma = [&](int x, int y) {
        return critical.gamma(2.0 * std::floor(est.count[est.index(0, x, y)]) - 2.0);
    };

    for (int yi = 0; yi < est.height; ++yi)
        for (int xi = 0; xi < est.width; ++xi) {
            double sum[kMaxEstimatorChannels] = {}, weight_sum = 1, members = 1;
            const double ni = std::isfinite(est.count[est.index(0, xi, yi)])
                                  ? est.count[est.index(0, xi, yi)]
                                  : 0.0;
            double inverse_sum = ni > 0 ? 1.0 / ni : 0.0;  // Σ W_ij² / n_j
            for (int c = 0; c < est.channels; ++c)
                sum[c] = est.value[est.index(c, xi, yi)];
            const bool centre_testable = est.testable(xi, yi);
            const double gi = centre_testable ? gamma(xi, yi) : 0.0;
            for (int yj = yi - r; yj <= yi + r && centre_testable; ++yj)
                for (int xj = xi - r; xj <= xi + r; ++xj) {
                    const double p2 = double(xj - xi) * (xj - xi) + double(yj - yi) * (yj - yi);
                    if (xj < 0 || yj < 0 || xj >= est.width || yj >= est.height ||
                        p2 > double(r) * r || (xj == xi && yj == yi) || !est.testable(xj, yj))
                        continue;
                    // The firefly guard (firefly_guard.h).
                    if (!(noise.level[pixel(xj, yj)] <= noise.limit[pixel(xi, yi)]) ||
                        !(noise.own[pixel(xi, yi)] <= noise.mutual_limit[pixel(xj, yj)]))
                        continue;
                    const double gj = gamma(xj, yj);
                    bool member = true;
                    for (int c = 0; c < est.channels; ++c) {
                        const double d = double(est.test_mean[est.index(c, xi, yi)]) -
                                         est.test_mean[est.index(c, xj, yj)];
                        const double bound = gi * gi * est.test_variance[est.index(c, xi, yi)] +
                                             gj * gj * est.test_variance[est.index(c, xj, yj)];
                        member = member && d * d <= bound;
                    }
                    if (!member)
                        continue;
                    const double log_w =
                        -p2 / (2.0 * double(options.sigma_spatial) * options.sigma_spatial) -
                        guide_exponent(est, guides, options, xi, yi, xj, yj);
                    const double w = std::exp(log_w);
                    for (int c = 0; c < est.channels; ++c)
                        sum[c] += w * est.value[est.index(c, xj, yj)];
                    weight_sum += w;
                    members += 1;
                    inverse_sum += w * w / est.count[est.index(0, xj, yj)];
                }
            for (int c = 0; c < est.channels; ++c)
                out[c](xi, yi) = float(sum[c] / weight_sum);
            if (diagnostics.members)
                diagnostics.members(xi, yi) = float(members);
            if (diagnostics.weight_sum)
                diagnostics.weight_sum(xi, yi) = float(weight_sum);
            if (diagnostics.effective_samples)
                diagnostics.effective_samples(xi, yi) =
                    inverse_sum > 0 ? float(weight_sum * weight_sum / inverse_sum) : 0.f;
        }
}

}  // namespace statmc
