#include "statmc/core/candidate_test.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
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

// One row's terms per channel, as the box sums read them: the difference x̄ − c, the
// variance of the mean ṽ/n and its v²/df (Welch–Satterthwaite), each 0 where the pixel
// cannot be tested (tested = 0), so that a box adds its taps without a branch.
struct RowTerms {
    std::vector<double> d, v, v2_over_df;
    std::vector<std::uint8_t> tested;
    explicit RowTerms(std::size_t size) : d(size), v(size), v2_over_df(size), tested(size) {}
};

// A row's box sums of one channel: the taps in raster order (rows, then x ascending), as
// a pixel-by-pixel loop would add them, but each tap offset across the whole row at once.
struct BoxSums {
    std::vector<double> d, v, v2_over_df;
    std::vector<int> count;
    explicit BoxSums(int w) : d(w), v(w), v2_over_df(w), count(w) {}

    void clear()
    {
        std::fill(d.begin(), d.end(), 0.0);
        std::fill(v.begin(), v.end(), 0.0);
        std::fill(v2_over_df.begin(), v2_over_df.end(), 0.0);
        std::fill(count.begin(), count.end(), 0);
    }
    void add_row(const RowTerms& t, std::size_t from, int w, int radius)
    {
        for (int dx = -radius; dx <= radius; ++dx) {
            const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
            const std::size_t at = from + std::size_t(x0 + dx);
            add(d.data() + x0, t.d.data() + at, x1 - x0);
            add(v.data() + x0, t.v.data() + at, x1 - x0);
            add(v2_over_df.data() + x0, t.v2_over_df.data() + at, x1 - x0);
            add(count.data() + x0, t.tested.data() + at, x1 - x0);
        }
    }
    template <class T, class U>
    static void add(T* __restrict sum, const U* __restrict term, int size)
    {
        for (int x = 0; x < size; ++x)
            sum[x] += term[x];
    }
};

// The critical value at `df` rounded down: a few degrees fewer only make the test more
// conservative, and the whole-number table spares a Boost quantile per pixel.
double critical(const CriticalValues& t, double df)
{
    return t.gamma(std::max(1.0, std::floor(df)));
}

// Rows per task: each task computes its rows' terms and the box's rows around them once.
constexpr int kRowsPerTask = 16;

}  // namespace

std::vector<std::uint8_t> test_candidate(const StatisticsView& stats,
                                         const std::vector<float>& variance,
                                         const std::vector<ConstPlane>& candidate,
                                         const CandidateTestOptions& o, int nthreads)
{
    require_valid(stats, variance, candidate, o);
    const int w = stats.width, h = stats.height, channels = stats.channels, b = o.box_radius;
    const std::size_t pixels = std::size_t(w) * h;
    const int tests = b > 0 ? 2 : 1;
    const double alpha_each = o.alpha / (tests * channels);
    const auto t = CriticalValues::shared(alpha_each, kMaxTabulatedDf);
    // Row y's terms into `out` (channel c at c·w); with `verdict`, its pixels' own tests.
    auto row_terms = [&](int y, RowTerms& out, std::uint8_t* verdict) {
        for (int x = 0; x < w; ++x) {
            const double n = stats.count(x, y), df = n - 1 + o.prior_dof;
            const double gamma2 = n >= 2 ? square(critical(*t, df)) : 0;
            const std::size_t i = std::size_t(y) * w + x;
            for (int c = 0; c < channels; ++c) {
                const std::size_t k = std::size_t(c) * w + x;
                const double s2 = variance[c * pixels + i];
                const double d = double(stats.mean[c](x, y)) - candidate[c](x, y);
                const bool tested = n >= 2 && std::isfinite(d) && std::isfinite(s2) && s2 >= 0;
                const double v = tested ? s2 / n : 0;
                out.d[k] = tested ? d : 0;
                out.v[k] = v;
                out.v2_over_df[k] = tested ? v * v / df : 0;
                out.tested[k] = tested;
                if (verdict && tested && d * d > gamma2 * v)
                    verdict[x] |= kRejectedByPixel;
            }
        }
    };
    std::vector<std::uint8_t> rejected(pixels, 0);
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, h, kRowsPerTask), [&](const auto& range) {
            // The task's rows and the box's rows around them, each row's terms made once.
            const int first = std::max(0, range.begin() - b);
            const int last = std::min(h, range.end() + b);
            std::vector<RowTerms> rows(last - first, RowTerms(std::size_t(channels) * w));
            for (int y = first; y < last; ++y) {
                const bool own = y >= range.begin() && y < range.end();
                row_terms(y, rows[y - first], own ? rejected.data() + std::size_t(y) * w : nullptr);
            }
            if (b == 0)
                return;
            // The mean difference over the box, its variance Σv/k² and the
            // Welch–Satterthwaite degrees of freedom (Σv)²/Σ(v²/df).
            BoxSums box(w);
            for (int y = range.begin(); y < range.end(); ++y)
                for (int c = 0; c < channels; ++c) {
                    box.clear();
                    for (int yy = std::max(0, y - b); yy <= std::min(h - 1, y + b); ++yy)
                        box.add_row(rows[yy - first], std::size_t(c) * w, w, b);
                    for (int x = 0; x < w; ++x) {
                        const int k = box.count[x];
                        if (k == 0)
                            continue;
                        const double mean = box.d[x] / k, var = box.v[x] / (double(k) * k);
                        const double v = box.v[x], v2 = box.v2_over_df[x];
                        // v2 = 0 only where every v is: then any df gives the same verdict.
                        const double df = v2 > 0 ? std::max(v * v / v2, 1.0) : 1.0;
                        if (mean * mean > square(critical(*t, df)) * var)
                            rejected[std::size_t(y) * w + x] |= kRejectedByBox;
                    }
                }
        });
    });
    return rejected;
}

}  // namespace statmc
