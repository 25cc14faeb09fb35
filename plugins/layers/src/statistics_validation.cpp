#include "statmc/layers/statistics_validation.h"

#include <cmath>
#include <functional>

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

struct Rule {
    std::function<bool(float)> bad;
    std::function<std::string(float)> what;
};

std::string format_value(float v) { return OIIO::Strutil::fmt::format("{}", v); }

Rule nonfinite_rule()
{
    return {[](float v) { return !std::isfinite(v); },
            [](float v) { return std::isnan(v) ? std::string("NaN") : v > 0 ? "Inf" : "-Inf"; }};
}

Rule negative_rule()
{
    return {[](float v) { return v < 0; },
            [](float v) { return "negative value " + format_value(v); }};
}

// 2√x − 2 ≥ −2 for every sample, so a smaller mean cannot come from the transform.
Rule box_cox_minimum_rule()
{
    return {[](float v) { return v < -2.f; },
            [](float v) { return "value " + format_value(v) + " below -2, the Box-Cox minimum"; }};
}

Rule count_rule()
{
    return {[](float n) { return n < 1.f; }, [](float n) { return "n = " + format_value(n); }};
}

void apply(const ConstPlane& plane, const std::string& channel, const Region& r, const Rule& rule,
           std::vector<StatisticsProblem>& problems)
{
    StatisticsProblem p;
    p.channel = channel;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const float v = plane(x, y);
            if (!rule.bad(v))
                continue;
            if (p.pixels++ == 0) {
                p.what = rule.what(v);
                p.x = x + r.origin_x;
                p.y = y + r.origin_y;
            }
        }
    if (p.pixels)
        problems.push_back(std::move(p));
}

std::vector<Rule> rules_for(Statistic stat)
{
    switch (stat) {
    case Statistic::Variance:
    case Statistic::BoxCoxVariance: return {negative_rule()};
    case Statistic::BoxCoxMean: return {box_cox_minimum_rule()};
    default: return {};
    }
}

Region region_of(const OIIO::ImageBuf& buf, OIIO::ROI roi)
{
    const OIIO::ImageSpec& spec = buf.spec();
    const OIIO::ROI r = roi.defined() ? OIIO::roi_intersection(roi, buf.roi()) : buf.roi();
    if (r.width() <= 0 || r.height() <= 0)
        return {0, 0, 0, 0, spec.x, spec.y};
    return {r.xbegin - spec.x, r.ybegin - spec.y, r.xend - spec.x, r.yend - spec.y,
            spec.x, spec.y};
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
    std::vector<StatisticsProblem> problems;
    auto check = [&](int index, const std::string& name, std::vector<Rule> rules) {
        if (options.nonfinite_is_problem)
            rules.insert(rules.begin(), nonfinite_rule());
        const ConstPlane plane = channel_plane(buf, index);
        for (const Rule& rule : rules)
            apply(plane, name, region, rule, problems);
    };
    check(channels.count, kSampleCountChannel, {count_rule()});
    for (Statistic stat : all_statistics())
        for (std::size_t c = 0; c < channels.indices(stat).size(); ++c)
            check(channels.indices(stat)[c], channels.channel(stat, int(c)), rules_for(stat));
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
