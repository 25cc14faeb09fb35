#include "joint_aovs.h"

#include "method_stages.h"
#include "statmc/core/filter.h"
#include "statmc/layers/layer_error.h"

namespace statmc::denoising {

using layers::LayerError;
using layers::Statistic;
using layers::StatisticsChannels;

namespace {

// Whether `ch` has what the test in `domain` reads.
bool has_test_statistics(const StatisticsChannels& ch, TestDomain domain)
{
    return domain == TestDomain::BoxCox ? ch.has_box_cox() : ch.has(Statistic::Variance);
}

}  // namespace

JointAovs plan_joint_aovs(const OIIO::ImageSpec& spec, const StatisticsChannels& lead,
                          TestDomain domain, const DenoiseImageOptions& opt)
{
    JointAovs joint;
    if (!opt.joint)
        return joint;
    joint.side_by_side = true;
    for (const std::string& aov : opt.aovs) {
        StatisticsChannels ch = layers::find_statistics(spec, aov);
        if (ch.channels() != lead.channels())
            throw LayerError("aovs: " + aov + " has " + std::to_string(ch.channels()) +
                             " channels and " + (lead.aov.empty() ? "the beauty" : lead.aov) + " " +
                             std::to_string(lead.channels()) + "; joint AOVs must match");
        if (joint.side_by_side && !has_test_statistics(ch, domain)) {
            joint.side_by_side = false;
            joint.note = "the joint AOVs' own tests (AOV " + aov + " has no " +
                         (domain == TestDomain::BoxCox ? "Box-Cox layers" : "variance") +
                         " of its own; the AOVs share " +
                         (opt.aov.empty() ? std::string("the beauty") : opt.aov) + "'s test)";
        }
        joint.channels.push_back(std::move(ch));
    }
    const int side_by_side_channels = lead.channels() * (1 + int(opt.aovs.size()));
    if (joint.side_by_side && !filter_takes_channels(side_by_side_channels)) {
        joint.side_by_side = false;
        joint.note = "the joint AOVs' own tests (" + std::to_string(side_by_side_channels) +
                     " channels side by side; the filter takes at most three RGB AOVs besides " +
                     (opt.aov.empty() ? std::string("the beauty") : opt.aov) +
                     ", whose test the AOVs share)";
    }
    return joint;
}

void check_joint_aovs(const OIIO::ImageBuf& in, JointAovs& joint, TestDomain domain,
                      const DenoiseImageOptions& opt, const OIIO::ROI& region)
{
    for (StatisticsChannels& ch : joint.channels) {
        if (joint.side_by_side) {
            ch = used_channels(ch, domain, false);
        } else {
            // Averaged with the lead's members, an AOV needs only its means and the count.
            for (Statistic stat : layers::all_statistics())
                if (stat != Statistic::Mean)
                    ch.indices(stat).clear();
        }
        check_statistics(in, ch, opt, region);
    }
}

}  // namespace statmc::denoising
