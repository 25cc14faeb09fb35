#include "statmc/render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"

namespace statmc::render {

namespace {

constexpr double kZ95 = 1.959963984540054;  // two-sided 95% normal quantile
constexpr double kRelMseEpsilon = 0.01;

// An iteration's floor and ceiling of samples per pixel, whole numbers so that carrying
// fractions along the scanline never crosses them.
struct Bounds {
    double lo, hi;
};

Bounds bounds_for(int spp, const AdaptiveSettings& s)
{
    const double lo = std::max(1.0, std::floor(s.min_rate * spp));
    return {lo, std::max(lo, std::floor(s.max_rate * spp))};
}

bool converged(double r, double n, const AdaptiveSettings& s)
{
    return s.noise_threshold > 0 && n >= s.min_spp && kZ95 * std::sqrt(r / n) <= s.noise_threshold;
}

}  // namespace

std::string AdaptiveSettings::validate() const
{
    char text[160];
    if (!(noise_threshold >= 0) || !std::isfinite(noise_threshold)) {
        std::snprintf(text, sizeof text, "noise threshold must be ≥ 0, got %g", noise_threshold);
        return text;
    }
    if (min_spp < 1) {
        std::snprintf(text, sizeof text, "minimum samples per pixel must be ≥ 1, got %d", min_spp);
        return text;
    }
    if (!(min_rate > 0 && min_rate <= 1)) {
        std::snprintf(text, sizeof text, "minimum rate must be in (0, 1], got %g", min_rate);
        return text;
    }
    if (!(max_rate >= 1) || !std::isfinite(max_rate)) {
        std::snprintf(text, sizeof text, "maximum rate must be ≥ 1, got %g", max_rate);
        return text;
    }
    return filter.validate();
}

std::string AdaptiveSettings::text() const
{
    if (!enabled)
        return "adaptive off";
    char text[160];
    std::snprintf(text, sizeof text, "adaptive threshold %g, min spp %d, rates %g..%g, radius %d",
                  noise_threshold, min_spp, min_rate, max_rate, filter.radius);
    return text;
}

namespace {

// The largest of each value and its neighbours at ±`step` along a line of `length` values
// `step` apart starting at `first` (clipped at the ends).
void line_max3(const std::vector<float>& in, std::vector<float>& out, std::size_t first,
               std::size_t step, int length)
{
    for (int k = 0; k < length; ++k) {
        float m = 0;
        for (int j = std::max(0, k - 1); j <= std::min(length - 1, k + 1); ++j)
            m = std::max(m, in[first + std::size_t(j) * step]);
        out[first + std::size_t(k) * step] = m;
    }
}

// The largest value of each 3×3 block (clipped at the borders): rows, then columns.
std::vector<float> block_max(const std::vector<float>& r, int w, int h)
{
    std::vector<float> rows(r.size()), out(r.size());
    for (int y = 0; y < h; ++y)
        line_max3(r, rows, std::size_t(y) * w, 1, w);
    for (int x = 0; x < w; ++x)
        line_max3(rows, out, std::size_t(x), std::size_t(w), h);
    return out;
}

}  // namespace

RelativeVariance relative_variance(const StatisticsImage<3>& stats, const DenoiseOptions& options,
                                   int threads)
{
    const int w = stats.width(), h = stats.height();
    const std::size_t npix = std::size_t(w) * h;
    const StatisticsPlanes planes = stats.planes();
    const EstimatorImage est = estimators_from_statistics(planes.view(), TestDomain::BoxCox);
    std::vector<float> mean(3 * npix), effective(npix);
    std::vector<Plane> out;
    for (int c = 0; c < 3; ++c)
        out.push_back(dense_plane(mean.data() + c * npix, w));
    FilterDiagnostics diagnostics;
    diagnostics.effective_samples = dense_plane(effective.data(), w);
    filter(est, {}, options, out, diagnostics, threads);

    std::vector<float> own(npix, 0.f), denoised(npix, 0.f);
    for (std::size_t i = 0; i < npix; ++i) {
        const double n = planes.count[i];
        if (!(n > 0) || !(effective[i] > 0))
            continue;
        double worst = 0;
        for (int c = 0; c < 3; ++c) {
            const double m = mean[c * npix + i], s2 = planes.variance[c * npix + i];
            worst = std::max(worst, s2 / (m * m + kRelMseEpsilon));
        }
        if (!(worst < std::numeric_limits<float>::max())) {
            // Unmeasurable: never converged, and no weight it could spread to the others.
            own[i] = std::numeric_limits<float>::max();
            continue;
        }
        own[i] = float(worst);
        denoised[i] = float(worst / std::max(1.0, double(effective[i]) / n));
    }
    return {block_max(own, w, h), block_max(denoised, w, h)};
}

SampleAllocation allocate_samples(const RelativeVariance& rv, const StatisticsImage<3>& stats,
                                  int spp, const AdaptiveSettings& settings)
{
    const std::vector<float>& relative_variance = rv.denoised;
    const std::size_t npix = relative_variance.size();
    const auto& pixels = stats.accumulators();
    const Bounds b = bounds_for(spp, settings);
    SampleAllocation alloc;
    alloc.counts.assign(npix, 0);

    // The pixels still sampled, and the budget they share.
    std::vector<char> active(npix, 0);
    std::size_t n_active = 0;
    for (std::size_t i = 0; i < npix; ++i) {
        active[i] = !converged(rv.own[i], pixels[i].n, settings);
        n_active += std::size_t(active[i]);
    }
    alloc.converged = npix - n_active;
    if (n_active == 0)
        return alloc;
    const double budget = double(spp) * double(n_active);

    // Each count in proportion to sqrt(r) (the total n + a = c·sqrt(r)), within the bounds;
    // the total is monotone in c, so bisection finds the c that spends the budget.
    std::vector<double> root(npix);
    for (std::size_t i = 0; i < npix; ++i)
        root[i] = std::sqrt(double(relative_variance[i]));
    auto share = [&](std::size_t i, double c) {
        return std::clamp(c * root[i] - pixels[i].n, b.lo, b.hi);
    };
    auto spent = [&](double c) {
        double sum = 0;
        for (std::size_t i = 0; i < npix; ++i)
            if (active[i])
                sum += share(i, c);
        return sum;
    };
    double c_hi = 0;
    for (std::size_t i = 0; i < npix; ++i)
        if (active[i] && root[i] > 0)
            c_hi = std::max(c_hi, (pixels[i].n + b.hi) / root[i]);
    double c = c_hi;
    if (spent(c_hi) > budget) {
        double c_lo = 0;
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (c_lo + c_hi);
            (spent(mid) > budget ? c_hi : c_lo) = mid;
        }
        c = c_lo;
    }
    // Whole samples: round the running sum, so every count is within one of its share and
    // never outside the (whole-number) bounds.
    double running = 0;
    std::uint64_t emitted = 0;
    for (std::size_t i = 0; i < npix; ++i) {
        if (!active[i])
            continue;
        running += share(i, c);
        const auto upto = std::uint64_t(std::llround(running));
        alloc.counts[i] = std::uint32_t(upto - emitted);
        emitted = upto;
    }
    alloc.total = emitted;
    return alloc;
}

}  // namespace statmc::render
