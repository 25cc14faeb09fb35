#include "statmc/layers/statistics_validation.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <OpenImageIO/strutil.h>

#include "statmc/layers/float_pixels.h"

namespace statmc::layers {

namespace {

// The pixels to check: a rectangle in view coordinates and the data window's corner,
// which turns them back into image coordinates for messages.
struct Region {
    int x0, y0, x1, y1;
    int origin_x, origin_y;
};

enum class Check { NonFinite, Negative, BelowBoxCoxMinimum, CountBelowOne };

std::string format_value(float v) { return OIIO::Strutil::fmt::format("{}", v); }

std::string describe(Check check, float v)
{
    switch (check) {
    case Check::NonFinite:
        return std::isnan(v) ? std::string("NaN") : v > 0 ? "Inf" : "-Inf";
    case Check::Negative:
        return "negative value " + format_value(v);
    // 2√x − 2 ≥ −2 for every sample, so a smaller mean cannot come from the transform.
    case Check::BelowBoxCoxMinimum:
        return "value " + format_value(v) + " below -2, the Box-Cox minimum";
    case Check::CountBelowOne:
        return "n = " + format_value(v);
    }
    return {};
}

bool is_bad(Check check, float v)
{
    switch (check) {
    case Check::NonFinite:
        return !std::isfinite(v);
    case Check::Negative:
        return v < 0;
    case Check::BelowBoxCoxMinimum:
        return v < -2.f;
    case Check::CountBelowOne:
        return v < 1.f;
    }
    return false;
}

/// The values each check accepts: is_bad(check, v) implies v ∉ [lo, hi] (NaN is in no
/// range), so a pixel inside every range of its checks passes them all.
struct Range {
    float lo = -std::numeric_limits<float>::infinity();
    float hi = std::numeric_limits<float>::infinity();
};

Range accepted(Check check)
{
    switch (check) {
    case Check::NonFinite:
        return {-FLT_MAX, FLT_MAX};
    case Check::Negative:
        return {0.f, Range{}.hi};
    case Check::BelowBoxCoxMinimum:
        return {-2.f, Range{}.hi};
    case Check::CountBelowOne:
        return {1.f, Range{}.hi};
    }
    return {};
}

/// One check of one channel, and what it found: how many bad pixels, and the first.
struct Task {
    ConstPlane plane;
    std::string channel;
    Check check;
};

struct Found {
    int count = 0;
    int first_x = -1;
};

/// A channel with the intersection of the ranges its checks accept.
struct Bound {
    ConstPlane plane;
    Range range;
};

std::vector<Bound> bounds_of(const std::vector<Task>& tasks)
{
    std::vector<Bound> bounds;
    for (const Task& t : tasks) {
        auto same = std::find_if(bounds.begin(), bounds.end(),
                                 [&](const Bound& b) { return b.plane.data == t.plane.data; });
        if (same == bounds.end())
            same = bounds.insert(bounds.end(), Bound{t.plane, {}});
        const Range r = accepted(t.check);
        same->range.lo = std::max(same->range.lo, r.lo);
        same->range.hi = std::min(same->range.hi, r.hi);
    }
    return bounds;
}

std::vector<Check> checks_for(Statistic stat)
{
    switch (stat) {
    case Statistic::Variance:
    case Statistic::BoxCoxVariance:
    case Statistic::Moment4:
    case Statistic::BoxCoxMoment4:
        return {Check::Negative};
    case Statistic::BoxCoxMean:
        return {Check::BelowBoxCoxMinimum};
    default:
        return {};
    }
}

// m2/n from a stored variance: s²·(n − 1)/n per sample (·n for a variance of the mean).
double second_moment(const ConstPlane& count, const ConstPlane& variance, bool of_mean, int x,
                     int y)
{
    const double n = count(x, y);
    const double s2 = double(variance(x, y)) * (of_mean ? n : 1.0);
    return n > 0 ? s2 * (n - 1) / n : 0.0;
}

bool sound(double v) { return std::isfinite(v) && v >= 0; }

// A relation between stored statistics that any set of samples satisfies, checked per
// pixel: M4/n ≥ (M2/n)² holds for any set of values (the mean of the squared squares is at
// least the square of their mean), so a stored fourth moment below it cannot come from
// samples; the slack absorbs float rounding of the two stored values. bad() says where it
// fails, what() describes the failure at that pixel. A plain type rather than a
// std::function: the check runs for every pixel, and an indirect call there was most of
// validation's time.
struct Relation {
    std::string channel;  ///< the channel named in the message
    ConstPlane count, variance;
    ConstPlane moment;     ///< M4/n
    bool of_mean = false;  ///< the variance is of the mean

    double limit(int x, int y) const
    {
        const double m2 = second_moment(count, variance, of_mean, x, y);
        return m2 * m2;
    }
    // True only where bad() is false, in double multiplications alone: bad() divides (and
    // takes a root) per pixel, which was most of validation's time. Each inequality is the
    // relation with its sides multiplied out by n (> 0), and is stricter than bad()'s own
    // slack by far more than the few double roundings here, so it never passes a pixel
    // that bad() rejects. A NaN anywhere fails it and leaves the pixel to bad().
    bool surely_good(int x, int y) const
    {
        const double n = count(x, y), m = moment(x, y);
        // M4/n ≥ m2², m2 = s²(n − 1)/n, times n²: the stored moment meets the bound.
        const double m2n = double(variance(x, y)) * (of_mean ? n : 1.0) * (n - 1);
        return (n >= 1) & (m * n * n >= m2n * m2n);
    }
    // A variance or moment that is itself wrong (negative, NaN) is reported by its own check.
    bool bad(int x, int y) const
    {
        const double m = moment(x, y);
        return sound(m) && sound(variance(x, y)) && m < (1 - 1e-5) * limit(x, y) - 1e-30;
    }
    std::string what(int x, int y) const
    {
        return OIIO::Strutil::fmt::format(
            "fourth moment {} below the square of the second, {}: inconsistent moments",
            moment(x, y), limit(x, y));
    }
};

// The first look at a row: is every checked value inside its channel's accepted range?
// When all checked channels lie in one interleaved pixel (an ImageBuf's own layout), a run
// of pixels is one run of floats, compared against the ranges repeated over kBlock pixels
// in a loop the compiler vectorises; channels laid out any other way are read one by one.
class RowScreen {
public:
    explicit RowScreen(std::vector<Bound> bounds) : bounds_(std::move(bounds))
    {
        if (bounds_.empty())
            return;
        const ConstPlane& first = bounds_.front().plane;
        const float* base = first.data;
        for (const Bound& b : bounds_) {
            if (b.plane.xstride != first.xstride || b.plane.ystride != first.ystride)
                return;
            base = std::min(base, b.plane.data);
        }
        const std::ptrdiff_t pixel = first.xstride;
        for (const Bound& b : bounds_)
            if (b.plane.data - base >= pixel)
                return;  // not within one pixel
        base_ = base;
        xstride_ = pixel;
        ystride_ = first.ystride;
        const std::size_t n = std::size_t(kBlock) * std::size_t(pixel);
        lo_.assign(n, 0.f);
        hi_.assign(n, 0.f);
        unchecked_.assign(n, 1);  // channels without a check (and other pixels' leading ones)
        for (const Bound& b : bounds_)
            for (int k = 0; k < kBlock; ++k) {
                const std::size_t j = std::size_t(k) * pixel + std::size_t(b.plane.data - base);
                lo_[j] = b.range.lo;
                hi_[j] = b.range.hi;
                unchecked_[j] = 0;
            }
    }

    bool passes(int x0, int x1, int y) const
    {
        int inside = 1;
        int x = x0;
        if (base_) {
            // A block's floats run from its first pixel's first checked channel into the
            // next pixel's unchecked leading ones, so the row's last pixel is always left
            // to the loop below: no read goes past the row.
            const int n = kBlock * int(xstride_);
            const float* lo = lo_.data();
            const float* hi = hi_.data();
            const int* unchecked = unchecked_.data();
            for (; x + kBlock < x1; x += kBlock) {
                const float* v =
                    base_ + std::ptrdiff_t(y) * ystride_ + std::ptrdiff_t(x) * xstride_;
                for (int j = 0; j < n; ++j)
                    inside &= (int(v[j] >= lo[j]) & int(v[j] <= hi[j])) | unchecked[j];
            }
        }
        for (; x < x1; ++x)
            for (const Bound& b : bounds_) {
                const float v = b.plane(x, y);
                inside &= int(v >= b.range.lo) & int(v <= b.range.hi);
            }
        return inside != 0;
    }

private:
    static constexpr int kBlock = 16;
    std::vector<Bound> bounds_;
    const float* base_ = nullptr;  // null: the channels are not one interleaved pixel
    std::ptrdiff_t xstride_ = 0, ystride_ = 0;
    std::vector<float> lo_, hi_;  // kBlock pixels' worth of each channel's range
    std::vector<int> unchecked_;  // 1 where no check applies
};

// One pass over the rows checks every channel and every relation: the channels of a pixel
// are adjacent in memory, so a pass per channel or per relation would read the whole image
// once for each (six relations took two thirds of validation's time that way). A row is
// first checked against each channel's accepted range, branch-free; only a row that fails
// it (a rare, bad row) runs the checks one by one to count and locate what is wrong. The
// relations are checked on the row while it is in cache. Rows run in parallel and are
// combined in order, so the pixel reported is always the first bad one in raster order.
void check_rows(const std::vector<Task>& tasks, const std::vector<Relation>& relations,
                const Region& r, std::vector<StatisticsProblem>& problems)
{
    const int rows = r.y1 - r.y0, n = int(tasks.size()), m = int(relations.size());
    if (rows <= 0 || n + m == 0)
        return;
    const RowScreen screen(bounds_of(tasks));
    // Per row, the tasks' findings and then the relations'.
    std::vector<Found> found(std::size_t(rows) * (n + m));
    tbb::parallel_for(
        tbb::blocked_range<int>(r.y0, r.y1, 16), [&](const tbb::blocked_range<int>& range) {
            for (int y = range.begin(); y < range.end(); ++y) {
                Found* row = &found[std::size_t(y - r.y0) * (n + m)];
                if (n > 0 && !screen.passes(r.x0, r.x1, y))
                    for (int x = r.x0; x < r.x1; ++x)
                        for (int t = 0; t < n; ++t)
                            if (is_bad(tasks[t].check, tasks[t].plane(x, y)) && row[t].count++ == 0)
                                row[t].first_x = x;
                for (int k = 0; k < m; ++k)
                    for (int x = r.x0; x < r.x1; ++x)
                        if (!relations[k].surely_good(x, y) && relations[k].bad(x, y) &&
                            row[n + k].count++ == 0)
                            row[n + k].first_x = x;
            }
        });
    // Column `col` of `found` as one problem of `channel`, described at its first pixel.
    auto report = [&](int col, const std::string& channel, auto&& what) {
        StatisticsProblem p;
        p.channel = channel;
        for (int y = r.y0; y < r.y1; ++y) {
            const Found& f = found[std::size_t(y - r.y0) * (n + m) + col];
            if (f.count && p.pixels == 0) {
                p.what = what(f.first_x, y);
                p.x = f.first_x + r.origin_x;
                p.y = y + r.origin_y;
            }
            p.pixels += f.count;
        }
        if (p.pixels)
            problems.push_back(std::move(p));
    };
    for (int t = 0; t < n; ++t)
        report(t, tasks[t].channel,
               [&](int x, int y) { return describe(tasks[t].check, tasks[t].plane(x, y)); });
    for (int k = 0; k < m; ++k)
        report(n + k, relations[k].channel, [&](int x, int y) { return relations[k].what(x, y); });
}

Region region_of(const OIIO::ImageBuf& buf, OIIO::ROI roi)
{
    const OIIO::ImageSpec& spec = buf.spec();
    const OIIO::ROI r = roi.defined() ? OIIO::roi_intersection(roi, buf.roi()) : buf.roi();
    if (r.width() <= 0 || r.height() <= 0)
        return {0, 0, 0, 0, spec.x, spec.y};
    return {r.xbegin - spec.x, r.ybegin - spec.y, r.xend - spec.x, r.yend - spec.y, spec.x, spec.y};
}

}  // namespace

std::string StatisticsProblem::message() const
{
    return OIIO::Strutil::fmt::format("{}: {} at pixel ({}, {}) [{} pixel{} affected]", channel,
                                      what, x, y, pixels, pixels == 1 ? "" : "s");
}

std::vector<StatisticsProblem> validate_statistics(const OIIO::ImageBuf& buf,
                                                   const StatisticsChannels& channels,
                                                   const ValidationOptions& options)
{
    const Region region = region_of(buf, options.roi);
    std::vector<Task> tasks;
    auto check = [&](int index, const std::string& name, std::vector<Check> checks) {
        if (options.nonfinite_is_problem)
            checks.insert(checks.begin(), Check::NonFinite);
        for (Check c : checks)
            tasks.push_back({channel_plane(buf, index), name, c});
    };
    check(channels.count, kSampleCountChannel, {Check::CountBelowOne});
    for (Statistic stat : all_statistics())
        for (std::size_t c = 0; c < channels.indices(stat).size(); ++c)
            check(channels.indices(stat)[c], channels.channel(stat, int(c)), checks_for(stat));
    std::vector<Relation> relations;
    const ConstPlane count = channel_plane(buf, channels.count);
    auto plane = [&](const std::vector<int>& indices, int c) {
        return channel_plane(buf, indices[c]);
    };
    for (int c = 0; c < channels.channels(); ++c) {
        // A fourth moment without its variance is not read (StatisticsView::has_moments).
        if (channels.has(Statistic::Moment4) && channels.has(Statistic::Variance))
            relations.push_back({channels.channel(Statistic::Moment4, c), count,
                                 plane(channels.variance, c), plane(channels.moment4, c),
                                 channels.variance_of_mean});
        if (channels.has(Statistic::BoxCoxMoment4) && channels.has_box_cox())
            relations.push_back({channels.channel(Statistic::BoxCoxMoment4, c), count,
                                 plane(channels.bc_variance, c), plane(channels.bc_moment4, c),
                                 false});
    }
    std::vector<StatisticsProblem> problems;
    check_rows(tasks, relations, region, problems);
    return problems;
}

std::string join_messages(const std::vector<StatisticsProblem>& problems)
{
    std::string text;
    for (const StatisticsProblem& p : problems)
        text += (text.empty() ? "" : "; ") + p.message();
    return text;
}

}  // namespace statmc::layers
