#include "statmc/render/bounce_statistics.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "statmc/layers/layer_names.h"

namespace statmc::render {

std::string BounceLayout::aov(int q) const
{
    using layers::BounceQuantity;
    if (q < luminance_bounces)
        return layers::bounce_aov(BounceQuantity::Luminance, q);
    const int m = q - luminance_bounces;
    return layers::bounce_aov(m % 2 == 0 ? BounceQuantity::LightWins : BounceQuantity::BsdfWins,
                              m / 2);
}

void bounce_sample(const PathRecord& record, const BounceLayout& layout, float* out)
{
    std::fill(out, out + layout.quantities(), 0.f);
    const int B = layout.luminance_bounces;
    if (B > 0) {
        // Sums by arrival vertex, the deepest tracked one taking everything beyond it;
        // then suffix sums give Σ over vertices ≥ j.
        Rgb sums[BounceLayout::kMaxLuminances];
        const int buckets = std::min(B, BounceLayout::kMaxLuminances);
        for (const auto& c : record.contributions)
            sums[std::min(c.arrival(), buckets - 1)] += c.value;
        Rgb suffix;
        for (int j = buckets - 1; j >= 0; --j) {
            suffix += sums[j];
            if (std::size_t(j) >= record.throughput.size())
                continue;  // the path never reached vertex j
            const Rgb beta = record.throughput[std::size_t(j)];
            Rgb l;
            for (int ch = 0; ch < 3; ++ch)
                l[ch] = beta[ch] > 0 ? suffix[ch] / beta[ch] : 0.f;  // no throughput, no light
            out[layout.luminance(j)] = l.luminance() * record.roulette_weight[std::size_t(j)];
        }
    }
    for (const auto& c : record.contributions) {
        if (c.technique == PathRecord::Technique::Emission || c.bounce >= layout.mis_bounces)
            continue;
        const bool own_win = c.mis_weight > 0.5f;
        const bool light_wins = (c.technique == PathRecord::Technique::Light) == own_win;
        out[light_wins ? layout.light_wins(c.bounce) : layout.bsdf_wins(c.bounce)] += 1.f;
    }
}

BounceStatistics::BounceStatistics(int width, int height, BounceLayout layout)
    : layout_(layout)
{
    if (layout.luminance_bounces < 0 || layout.luminance_bounces > BounceLayout::kMaxLuminances ||
        layout.mis_bounces < 0)
        throw std::invalid_argument("BounceStatistics: at most " +
                                    std::to_string(BounceLayout::kMaxLuminances) +
                                    " luminances and a non-negative number of MIS bounces");
    const int groups = (layout.quantities() + kGroup - 1) / kGroup;
    groups_.reserve(std::size_t(groups));
    for (int g = 0; g < groups; ++g)
        groups_.emplace_back(width, height);
}

void BounceStatistics::add(int x, int y, const float* values)
{
    const int q = layout_.quantities();
    for (std::size_t g = 0; g < groups_.size(); ++g) {
        float packed[kGroup] = {0, 0, 0, 0};  // the last group's spare channels stay 0
        const int first = int(g) * kGroup;
        std::copy(values + first, values + std::min(q, first + kGroup), packed);
        groups_[g].add(x, y, packed);
    }
}

std::vector<StatisticsPlanes> BounceStatistics::group_planes() const
{
    std::vector<StatisticsPlanes> out;
    out.reserve(groups_.size());
    for (const auto& g : groups_)
        out.push_back(g.planes());
    return out;
}

StatisticsView BounceStatistics::quantity_view(const std::vector<StatisticsPlanes>& groups, int q)
{
    const StatisticsView group = groups.at(std::size_t(q / kGroup)).view();
    const int c = q % kGroup;
    StatisticsView v = group;
    v.channels = 1;
    v.mean = {group.mean[c]};
    v.variance = {group.variance[c]};
    v.bc_mean = {group.bc_mean[c]};
    v.bc_variance = {group.bc_variance[c]};
    v.bc_moment3 = {group.bc_moment3[c]};
    v.moment3 = {group.moment3[c]};
    v.moment4 = {group.moment4[c]};
    v.bc_moment4 = {group.bc_moment4[c]};
    return v;
}

}  // namespace statmc::render
