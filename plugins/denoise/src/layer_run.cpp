#include "layer_run.h"

#include <array>
#include <utility>
#include <vector>

#include "denoised_image.h"
#include "joint_aovs.h"
#include "mean_filter.h"
#include "method_stages.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/view_window.h"
#include "temporal_frames.h"

namespace statmc::denoising {

using layers::StatisticsChannels;

namespace {

std::array<ConstPlane, 3> guide(const OIIO::ImageBuf& in, GuideUse use, const std::string& layer,
                                bool colour)
{
    if (use == GuideUse::Off)
        return {};
    const std::vector<int> indices = use == GuideUse::Required
                                         ? layers::require_guide_layer(in.spec(), layer, colour)
                                         : layers::find_guide_layer(in.spec(), layer, colour);
    return indices.empty() ? std::array<ConstPlane, 3>{} : layers::guide_planes(in, indices);
}

// Both guides and their variances, as `opt` asks for them.
layers::GuidePlanes guides_of(const OIIO::ImageBuf& in, const GuideSelection& use)
{
    layers::GuidePlanes guides;
    guides.albedo = guide(in, use.albedo, use.albedo_layer, true);
    guides.normal = guide(in, use.normal, use.normal_layer, false);
    if (guides.albedo[0])
        guides.albedo_variance = layers::guide_variance_plane(in, use.albedo_layer);
    if (guides.normal[0])
        guides.normal_variance = layers::guide_variance_plane(in, use.normal_layer);
    return guides;
}

}  // namespace

std::string denoise_layer(const OIIO::ImageBuf& in, OIIO::ImageBuf& out,
                          const FrameNeighbours& neighbours, const DenoiseImageOptions& run,
                          const OIIO::ROI& roi, const PixelMask& where, int nthreads)
{
    const OIIO::ImageSpec& spec = in.spec();
    const StatisticsChannels all = layers::find_statistics(spec, run.aov);
    const TestDomain domain = choose_domain(spec, all, run.test);
    JointAovs joint = plan_joint_aovs(spec, all, domain, run);
    const Stages stages = stages_for(all, joint.side_by_side, run);
    const StatisticsChannels ch = used_channels(all, domain, stages.radius_ladder);
    const Regions regions = regions_for(in, roi, run.filter.radius + stages.halo(), where);
    check_statistics(in, ch, run, regions.input);
    check_joint_aovs(in, joint, domain, run, regions.input);
    const layers::GuidePlanes guides = guides_of(in, run.guides);

    StatisticsView full = layers::statistics_view(in, ch);
    StatisticsPlanes merged;
    if (run.temporal.frames > 0 && (!neighbours.previous.empty() || !neighbours.next.empty())) {
        merged = merged_over_time(in, ch, domain, neighbours, run, nthreads);
        full = with_planes_of(full, merged.view());
    }
    const int x0 = regions.input.xbegin - spec.x;
    const int y0 = regions.input.ybegin - spec.y;
    const int width = regions.input.width(), height = regions.input.height();
    const StatisticsView window = layers::view_window(full, x0, y0, width, height);
    const Guides window_guides{layers::shifted(guides.albedo, x0, y0),
                               layers::shifted(guides.normal, x0, y0),
                               layers::shifted(guides.albedo_variance, x0, y0),
                               layers::shifted(guides.normal_variance, x0, y0)};
    auto aov_window = [&](const StatisticsChannels& aov_ch) {
        return layers::view_window(layers::statistics_view(in, aov_ch), x0, y0, width, height);
    };

    Filtered filtered;
    std::vector<Filtered> joint_filtered;
    if (joint.side_by_side) {
        // One filter over the lead and every AOV side by side: all their tests decide.
        std::vector<StatisticsView> views;
        for (const StatisticsChannels& aov_ch : joint.channels)
            views.push_back(aov_window(aov_ch));
        std::vector<Filtered> together = filter_joint_all(window, views, domain, window_guides,
                                                          run.filter, regions.wanted, nthreads);
        filtered = std::move(together[0]);
        joint_filtered.assign(std::make_move_iterator(together.begin() + 1),
                              std::make_move_iterator(together.end()));
    } else {
        // Built once: the joint AOVs below reuse the lead's estimators, their values swapped.
        EstimatorImage lead =
            lead_estimators(window, domain, run.filter, stages.context_radius, nthreads);
        filtered = filter_region(window, lead, window_guides, run.filter, run.diagnostics,
                                 stages.radius_ladder ? &stages.ladder : nullptr, regions.wanted,
                                 nthreads);
        for (const StatisticsChannels& aov_ch : joint.channels)
            joint_filtered.push_back(filter_joint_aov(lead, aov_window(aov_ch), window_guides,
                                                      run.filter, regions.wanted, nthreads));
    }

    if (&out == &in)
        write_channels(out, nullptr, mean_writes(ch, filtered, regions), regions, nthreads);
    else
        out = denoised_copy(in, ch, filtered, regions, nthreads);
    std::vector<ChannelWrite> joint_writes;
    for (std::size_t k = 0; k < joint.channels.size(); ++k)
        for (const ChannelWrite& w : mean_writes(joint.channels[k], joint_filtered[k], regions))
            joint_writes.push_back(w);
    if (!joint_writes.empty())
        write_channels(out, nullptr, joint_writes, regions, nthreads);
    if (run.diagnostics) {
        int members = -1, effective = -1;
        out = with_diagnostics_channels(out, run.aov, members, effective);
        write_channels(
            out, nullptr,
            {{members, filtered.members.data()}, {effective, filtered.effective_samples.data()}},
            regions, nthreads);
    }
    std::string skipped = stages.skipped;
    if (!joint.note.empty())
        skipped += (skipped.empty() ? "" : "; ") + joint.note;
    return skipped;
}

}  // namespace statmc::denoising
