#include "statmc/core/candidate_test.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/thread_limit.h"

namespace statmc {

namespace {

// Tabulated to this many degrees of freedom; beyond it the table interpolates to the normal.
constexpr double kMaxTabulatedDf = 1e6;

double square(double v) { return v * v; }

void require_valid(const StatisticsView& stats, const std::vector<float>& variance,
                   const std::vector<ConstPlane>& candidate, const CandidateTestOptions& o)
{
    if (!(o.alpha > 0 && o.alpha < 1))
        throw std::invalid_argument("candidate test: alpha must be in (0, 1)");
    if (o.box_radius < 0)
        throw std::invalid_argument("candidate test: the box radius must be >= 0");
    if (!(o.prior_dof >= 0 && std::isfinite(o.prior_dof)))
        throw std::invalid_argument("candidate test: prior_dof must be finite and >= 0");
    if (!stats.count || stats.channels < 1)
        throw std::invalid_argument("candidate test: statistics lack a count or a mean");
    if (int(candidate.size()) != stats.channels)
        throw std::invalid_argument("candidate test: one candidate plane per channel is needed");
    for (int c = 0; c < stats.channels; ++c)
        if (!stats.mean[c] || !candidate[c])
            throw std::invalid_argument("candidate test: a mean or candidate plane is missing");
    if (variance.size() != std::size_t(stats.width) * stats.height * stats.channels)
        throw std::invalid_argument("candidate test: the variances do not match the statistics");
}

// One pixel and channel's difference from the candidate, the variance of its mean and
// its degrees of freedom; df = 0 where the pixel cannot be tested.
struct Difference {
    double d = 0, v = 0, df = 0;
};

// The critical value at `df` rounded down: a few degrees fewer only make the test more
// conservative, and the whole-number table spares a Boost quantile per pixel.
double critical(const CriticalValues& t, double df)
{
    return t.gamma(std::max(1.0, std::floor(df)));
}

}  // namespace

std::vector<std::uint8_t> test_candidate(const StatisticsView& stats,
                                         const std::vector<float>& variance,
                                         const std::vector<ConstPlane>& candidate,
                                         const CandidateTestOptions& o, int nthreads)
{
    require_valid(stats, variance, candidate, o);
    const int w = stats.width, h = stats.height, channels = stats.channels;
    const std::size_t pixels = std::size_t(w) * h;
    const int tests = o.box_radius > 0 ? 2 : 1;
    const double alpha_each = o.alpha / (tests * channels);
    const auto t = CriticalValues::shared(alpha_each, kMaxTabulatedDf);
    std::vector<Difference> diff(pixels * channels);
    std::vector<std::uint8_t> rejected(pixels, 0);
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const double n = stats.count(x, y);
                const std::size_t i = std::size_t(y) * w + x;
                for (int c = 0; c < channels; ++c) {
                    const double s2 = variance[c * pixels + i];
                    const double d = double(stats.mean[c](x, y)) - candidate[c](x, y);
                    Difference& out = diff[c * pixels + i];
                    if (n >= 2 && std::isfinite(d) && std::isfinite(s2) && s2 >= 0)
                        out = {d, s2 / n, n - 1 + o.prior_dof};
                }
            }
        });
        tbb::parallel_for(0, h, [&](int y) {
            const int y0 = std::max(0, y - o.box_radius), y1 = std::min(h - 1, y + o.box_radius);
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const int x0 = std::max(0, x - o.box_radius);
                const int x1 = std::min(w - 1, x + o.box_radius);
                std::uint8_t verdict = 0;
                for (int c = 0; c < channels; ++c) {
                    const Difference& own = diff[c * pixels + i];
                    if (own.df > 0 && own.d * own.d > square(critical(*t, own.df)) * own.v)
                        verdict |= kRejectedByPixel;
                    if (o.box_radius == 0)
                        continue;
                    // The mean difference over the box, its variance Σv/k² and the
                    // Welch–Satterthwaite degrees of freedom (Σv)²/Σ(v²/df).
                    double sum = 0, v = 0, v2_over_df = 0;
                    int k = 0;
                    for (int yy = y0; yy <= y1; ++yy)
                        for (int xx = x0; xx <= x1; ++xx) {
                            const Difference& q = diff[c * pixels + std::size_t(yy) * w + xx];
                            if (q.df <= 0)
                                continue;
                            sum += q.d;
                            v += q.v;
                            v2_over_df += q.v * q.v / q.df;
                            ++k;
                        }
                    if (k == 0)
                        continue;
                    const double mean = sum / k, var = v / (double(k) * k);
                    const double df = v2_over_df > 0 ? v * v / v2_over_df : own.df;
                    if (mean * mean > square(critical(*t, std::max(df, 1.0))) * var)
                        verdict |= kRejectedByBox;
                }
                rejected[i] = verdict;
            }
        });
    });
    return rejected;
}

}  // namespace statmc
