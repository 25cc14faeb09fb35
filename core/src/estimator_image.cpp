#include "statmc/core/estimator_image.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "statmc/core/box_cox.h"

namespace statmc {

namespace {

constexpr float kUntestable = std::numeric_limits<float>::quiet_NaN();

void require_channels(int channels)
{
    if (channels < 1 || channels > kMaxEstimatorChannels)
        throw std::invalid_argument("estimators have 1 to " +
                                    std::to_string(kMaxEstimatorChannels) + " channels, got " +
                                    std::to_string(channels));
}

// Marks pixel (x, y) untestable in every channel, so that no test involving it passes.
void mark_untestable(EstimatorImage& est, int x, int y)
{
    for (int c = 0; c < est.channels; ++c) {
        est.test_mean[est.index(c, x, y)] = 0;
        est.test_variance[est.index(c, x, y)] = kUntestable;
    }
}

// EstimatorImage::support of pixel (x, y): the effective count of its brightest channel's
// sample values; +∞ where that channel is all zero (nothing rests on few samples there).
float sample_support(const StatisticsView& stats, int x, int y)
{
    const double n = stats.count(x, y);
    int brightest = 0;
    for (int c = 1; c < stats.channels; ++c)
        if (stats.mean[c](x, y) > stats.mean[brightest](x, y))
            brightest = c;
    const double m = stats.mean[brightest](x, y), v = stats.variance[brightest](x, y);
    const double per_sample = stats.variance_of_mean ? v * n : v;
    const double square = m * m + per_sample * (n - 1) / std::max(n, 1.0);  // mean of x²
    if (!(n >= 1) || !std::isfinite(square) || !std::isfinite(m))
        return 0.f;
    return square > 0 ? float(n * m * m / square) : std::numeric_limits<float>::infinity();
}

// Pixel (x, y) of `est` from the statistics, in the chosen test domain.
void fill_estimator(EstimatorImage& est, const StatisticsView& stats, TestDomain domain, int x,
                    int y)
{
    const float n = stats.count(x, y);
    est.count[est.index(0, x, y)] = n;
    const bool enough_samples = n >= 2;  // else s² and every ratio below are undefined
    bool finite_value = true;
    for (int c = 0; c < stats.channels; ++c) {
        const float f = stats.mean[c](x, y);
        finite_value = finite_value && std::isfinite(f);
        est.value[est.index(c, x, y)] = std::isfinite(f) ? f : 0.f;
        float mu = 0.f, v = 0.f;
        if (!enough_samples) {
            // left untestable below
        } else if (domain == TestDomain::BoxCox) {
            const float s2 = stats.bc_variance[c](x, y);
            const float m3 = stats.bc_moment3[c](x, y);
            // Johnson's (1978) first-order skewness correction of the mean.
            const float skew = s2 > FLT_EPSILON ? m3 / (6.f * s2 * n) : 0.f;
            mu = stats.bc_mean[c](x, y) + skew;
            v = s2 / n;
        } else {
            mu = f;
            const float var = stats.variance[c](x, y);
            v = stats.variance_of_mean ? var : var / n;
        }
        est.test_mean[est.index(c, x, y)] = mu;
        est.test_variance[est.index(c, x, y)] = v;
    }
    if (!finite_value || !est.testable(x, y))
        mark_untestable(est, x, y);
    if (!est.support.empty())
        est.support[std::size_t(y) * est.width + x] = sample_support(stats, x, y);
}

}  // namespace

void EstimatorImage::testable_row(int y, std::uint8_t* out) const
{
    // Locals: a byte store may alias anything, members included, which would keep the
    // compiler from vectorising loops bounded by `width`.
    const int w = width, k = channels;
    const float* n = count.data() + index(0, 0, y);
    for (int x = 0; x < w; ++x)
        out[x] = n[x] >= 2;
    for (int c = 0; c < k; ++c) {
        const float* mean = test_mean.data() + index(c, 0, y);
        const float* variance = test_variance.data() + index(c, 0, y);
        for (int x = 0; x < w; ++x)
            out[x] &= testable_estimate(mean[x], variance[x]);
    }
}

EstimatorImage::EstimatorImage(int w, int h, int c) : width(w), height(h), channels(c)
{
    require_channels(c);
    if (w <= 0 || h <= 0)
        throw std::invalid_argument("empty resolution");
    // ~50 MB at 1280×720 RGB: filling the planes side by side shares the page faults
    // and stores of first touch between the threads.
    tbb::parallel_invoke([&] { count.assign(pixels(), 0.f); },
                         [&] { value.assign(pixels() * c, 0.f); },
                         [&] { test_mean.assign(pixels() * c, 0.f); },
                         [&] { test_variance.assign(pixels() * c, kUntestable); });
}

EstimatorImage estimators_from_statistics(const StatisticsView& stats, TestDomain domain)
{
    require_channels(stats.channels);
    if (!stats.count)
        throw std::invalid_argument("statistics lack a sample count plane");
    for (int c = 0; c < stats.channels; ++c) {
        if (!stats.mean[c])
            throw std::invalid_argument("statistics lack a mean plane");
        if (domain == TestDomain::Untransformed && !stats.variance[c])
            throw std::invalid_argument("statistics lack a variance plane");
    }
    if (domain == TestDomain::BoxCox && !stats.has_box_cox())
        throw std::invalid_argument("statistics lack the Box-Cox planes");

    EstimatorImage est(stats.width, stats.height, stats.channels);
    est.domain = domain;
    if (stats.has_variance())
        est.support.assign(est.pixels(), 0.f);
    // Rows are independent; threads only split the work.
    tbb::parallel_for(tbb::blocked_range<int>(0, stats.height, 16),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (int y = rows.begin(); y < rows.end(); ++y)
                              for (int x = 0; x < stats.width; ++x)
                                  fill_estimator(est, stats, domain, x, y);
                      });
    return est;
}

EstimatorImage side_by_side(const std::vector<const EstimatorImage*>& parts)
{
    if (parts.empty())
        throw std::invalid_argument("side_by_side: no images");
    const EstimatorImage& first = *parts[0];
    int channels = 0;
    for (const EstimatorImage* p : parts) {
        if (p->width != first.width || p->height != first.height || p->domain != first.domain)
            throw std::invalid_argument("side_by_side: the images differ in size or test domain");
        if (p->count != first.count)
            throw std::invalid_argument("side_by_side: the images differ in their sample counts");
        if (p->context_channels > 0)
            throw std::invalid_argument("side_by_side: context channels must come last");
        channels += p->channels;
    }
    EstimatorImage out(first.width, first.height, channels);
    out.domain = first.domain;
    out.count = first.count;
    out.support = first.support;  // the lead's: the guard guards the lead
    std::size_t at = 0;
    for (const EstimatorImage* p : parts) {
        const std::size_t n = p->value.size();
        std::copy(p->value.begin(), p->value.end(), out.value.begin() + at);
        std::copy(p->test_mean.begin(), p->test_mean.end(), out.test_mean.begin() + at);
        std::copy(p->test_variance.begin(), p->test_variance.end(), out.test_variance.begin() + at);
        at += n;
    }
    return out;
}

}  // namespace statmc
