#include "method_stages.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/statistics_validation.h"

namespace statmc::denoising {

using layers::LayerError;
using layers::Statistic;
using layers::StatisticsChannels;

Regions regions_for(const OIIO::ImageBuf& src, const OIIO::ROI& roi, int radius,
                    const PixelMask& where)
{
    const OIIO::ROI data = src.roi();
    const OIIO::ROI output = roi.defined() ? OIIO::roi_intersection(roi, data) : data;
    if (output.width() <= 0 || output.height() <= 0)
        throw std::invalid_argument("the ROI does not overlap the data window");
    OIIO::ROI input = output;
    input.xbegin -= radius;
    input.xend += radius;
    input.ybegin -= radius;
    input.yend += radius;
    Regions r{output, OIIO::roi_intersection(input, data), {}};
    if (where.empty())
        return r;
    const OIIO::ImageSpec& spec = src.spec();
    require_mask_fits(where, spec.width, spec.height);
    r.wanted.assign(std::size_t(r.input.width()) * r.input.height(), 0);
    for (int y = output.ybegin; y < output.yend; ++y)
        for (int x = output.xbegin; x < output.xend; ++x)
            r.wanted[std::size_t(y - r.input.ybegin) * r.input.width() + (x - r.input.xbegin)] =
                where[std::size_t(y - spec.y) * spec.width + (x - spec.x)] != 0;
    return r;
}

TestDomain choose_domain(const OIIO::ImageSpec& spec, const StatisticsChannels& ch,
                         TestDomainChoice choice)
{
    switch (choice) {
    case TestDomainChoice::Auto:
        if (ch.has_box_cox())
            return TestDomain::BoxCox;
        if (!ch.has(Statistic::Variance))
            throw LayerError(layers::missing_layer_message(
                spec, layers::statistic_layer(ch.aov, Statistic::Variance), ch.suffixes, "layer",
                "denoising needs it or the Box-Cox layers (boxcoxMean, "
                "boxcoxVariance, boxcoxM3)"));
        return TestDomain::Untransformed;
    case TestDomainChoice::BoxCox:
        for (Statistic stat :
             {Statistic::BoxCoxMean, Statistic::BoxCoxVariance, Statistic::BoxCoxMoment3})
            layers::require_statistic(spec, ch, stat);
        return TestDomain::BoxCox;
    case TestDomainChoice::Untransformed:
        layers::require_statistic(spec, ch, Statistic::Variance);
        return TestDomain::Untransformed;
    }
    throw std::invalid_argument("unknown test domain");
}

// Only the statistics the stages read are checked and viewed: the test's, and the
// untransformed variance for the radius ladder (`variance`).
StatisticsChannels used_channels(StatisticsChannels ch, TestDomain domain, bool variance)
{
    for (auto* v : {&ch.moment3, &ch.moment4, &ch.bc_moment4})
        v->clear();
    if (domain == TestDomain::BoxCox) {
        if (!variance)
            ch.variance.clear();
    } else {
        ch.bc_mean.clear();
        ch.bc_variance.clear();
        ch.bc_moment3.clear();
    }
    return ch;
}

void check_statistics(const OIIO::ImageBuf& in, const StatisticsChannels& ch,
                      const DenoiseImageOptions& opt, const OIIO::ROI& region)
{
    layers::ValidationOptions options;
    options.nonfinite_is_problem = opt.nonfinite == NonfinitePolicy::Error;
    options.roi = region;
    const auto problems = layers::validate_statistics(in, ch, options);
    if (!problems.empty())
        throw LayerError(layers::join_messages(problems));
}

Stages stages_for(const StatisticsChannels& all, bool side_by_side, const DenoiseImageOptions& opt)
{
    Stages s;
    auto skip = [&s](const std::string& why) {
        s.skipped += (s.skipped.empty() ? "" : "; ") + why;
    };
    s.radius_ladder = opt.stages.radius_ladder;
    if (s.radius_ladder) {
        const char* why = opt.joint ? "joint AOVs share one membership; the ladder's radii "
                                      "would differ per AOV"
                          : !all.has(Statistic::Variance) ? "needs the variance layer"
                          : opt.diagnostics ? "the radius differs per pixel, so diagnostics "
                                              "cannot describe it"
                                            : nullptr;
        if (why) {
            s.radius_ladder = false;
            skip(std::string("ici (") + why + ")");
        }
    }
    if (s.radius_ladder) {
        s.ladder = opt.stages.ladder;
        // Its variance filter weighs the guides as the mean filter does.
        s.ladder.variance.sigma_albedo = opt.filter.sigma_albedo;
        s.ladder.variance.sigma_normal = opt.filter.sigma_normal;
    }
    s.context_radius = opt.stages.context_radius;
    if (s.context_radius > 0) {
        // The lead's membership alone would change: joint AOVs would no longer add up.
        const char* why = side_by_side ? "the AOVs are tested side by side, and the filter has no "
                                         "room for a context channel beside them"
                          : all.channels() >= 4 ? "the filter takes at most four channels, "
                                                  "and the layer has four without it"
                                                : nullptr;
        if (why) {
            s.context_radius = 0;
            skip(std::string("context (") + why + ")");
        }
    }
    return s;
}

}  // namespace statmc::denoising
