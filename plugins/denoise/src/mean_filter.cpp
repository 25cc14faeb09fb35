#include "mean_filter.h"

#include <stdexcept>
#include <string>

#include "statmc/core/context_channel.h"
#include "statmc/layers/imagebufalgo_forms.h"

namespace statmc::denoising {

EstimatorImage lead_estimators(const StatisticsView& stats, TestDomain domain,
                               const DenoiseOptions& options, int context, int nthreads)
{
    EstimatorImage est = estimators_from_statistics(stats, domain);
    if (context == 0)
        return est;
    return with_context(est, context_source_channel(est.channels), context, options.firefly_ratio,
                        layers::thread_count(nthreads));
}

Filtered filter_region(const StatisticsView& stats, const EstimatorImage& est, const Guides& guides,
                       const DenoiseOptions& options, bool diagnostics,
                       const RadiusLadderOptions* ladder, const PixelMask& wanted, int nthreads)
{
    const std::size_t pixels = std::size_t(stats.width) * stats.height;
    Filtered f;
    f.means.resize(pixels * stats.channels);
    std::vector<Plane> out;  // none for the context channel, which is only tested
    for (int c = 0; c < stats.channels; ++c)
        out.push_back(dense_plane(f.means.data() + c * pixels, stats.width));
    FilterDiagnostics planes;
    if (diagnostics) {
        f.members.resize(pixels);
        f.effective_samples.resize(pixels);
        planes.members = dense_plane(f.members.data(), stats.width);
        planes.effective_samples = dense_plane(f.effective_samples.data(), stats.width);
    }
    if (ladder)
        filter_with_radius_ladder(stats, est, guides, options, out, *ladder,
                                  layers::thread_count(nthreads), wanted);
    else
        filter(est, guides, options, out, planes, layers::thread_count(nthreads), SimdLevel::Auto,
               wanted);
    return f;
}

Filtered filter_joint_aov(EstimatorImage& lead, const StatisticsView& aov, const Guides& guides,
                          const DenoiseOptions& options, const PixelMask& wanted, int nthreads)
{
    const int own = lead.channels - lead.context_channels;  // the context's are only tested
    for (int c = 0; c < own; ++c)
        for (int y = 0; y < lead.height; ++y)
            for (int x = 0; x < lead.width; ++x)
                lead.value[lead.index(c, x, y)] = aov.mean[c](x, y);
    Filtered f;
    f.means.resize(lead.pixels() * own);
    std::vector<Plane> out;
    for (int c = 0; c < own; ++c)
        out.push_back(dense_plane(f.means.data() + c * lead.pixels(), lead.width));
    filter(lead, guides, options, out, {}, layers::thread_count(nthreads), SimdLevel::Auto, wanted);
    return f;
}

std::vector<Filtered> filter_joint_all(const StatisticsView& lead,
                                       const std::vector<StatisticsView>& aovs, TestDomain domain,
                                       const Guides& guides, const DenoiseOptions& options,
                                       const PixelMask& wanted, int nthreads)
{
    std::vector<EstimatorImage> parts = {estimators_from_statistics(lead, domain)};
    for (const StatisticsView& aov : aovs)
        parts.push_back(estimators_from_statistics(aov, domain));
    std::vector<const EstimatorImage*> pointers;
    for (const EstimatorImage& p : parts)
        pointers.push_back(&p);
    const EstimatorImage all = side_by_side(pointers);
    if (!filter_takes_channels(all.channels))
        throw std::logic_error("joint AOVs side by side make " + std::to_string(all.channels) +
                               " channels, which the filter does not take");
    std::vector<float> means(all.pixels() * all.channels);
    std::vector<Plane> out;
    for (int c = 0; c < all.channels; ++c)
        out.push_back(dense_plane(means.data() + c * all.pixels(), all.width));
    filter(all, guides, options, out, {}, layers::thread_count(nthreads), SimdLevel::Auto, wanted);
    std::vector<Filtered> result(parts.size());
    std::size_t at = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const std::size_t n = parts[k].pixels() * parts[k].channels;
        result[k].means.assign(means.begin() + at, means.begin() + at + n);
        at += n;
    }
    return result;
}

}  // namespace statmc::denoising
