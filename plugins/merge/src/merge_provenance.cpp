#include "statmc/merge/merge_provenance.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <stdexcept>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/frame_match.h"

namespace statmc {

namespace {

using Parts = std::vector<const OIIO::ImageBuf*>;

// More tasks than this is a damaged header, not a split: the task table stays small.
constexpr int kMaxTasks = 1 << 20;

std::string label(const Parts& parts, std::size_t k)
{
    return layers::input_label("part", k, parts[k]);
}

// "part 2 (b.exr: seed 0, samples 0..15, task 1/4)".
std::string label(const Parts& parts, std::size_t k, const layers::SampleProvenance& p)
{
    const std::string name = parts[k]->name();
    return "part " + std::to_string(k) + " (" + (name.empty() ? "" : name + ": ") +
           layers::describe(p) + ")";
}

std::vector<layers::SampleProvenance> read_all(const Parts& parts)
{
    std::vector<layers::SampleProvenance> all;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        try {
            all.push_back(layers::read_sample_provenance(parts[k]->spec()));
        } catch (const layers::LayerError& e) {
            throw std::invalid_argument(label(parts, k) + ": " + e.what());
        }
    }
    return all;
}

void refuse_overlaps(const Parts& parts, const std::vector<layers::SampleProvenance>& all)
{
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j) {
            const auto &a = all[i], &b = all[j];
            if (layers::shares_samples(a, b))
                throw std::invalid_argument(
                    label(parts, i, a) + " and " + label(parts, j, b) +
                    " drew the same samples: merged, they would count twice. Render the "
                    "parts with different --seed values, or as tasks of one frame (--task I/N)");
        }
}

// A task whose pixels hold fewer samples than its range: it was stopped (statmc:spp is
// then absent, statmc:sppMin short).
bool stopped_early(const OIIO::ImageBuf& part, const layers::SampleProvenance& p)
{
    const OIIO::ParamValue* spp = part.spec().find_attribute(layers::attr::kSpp, OIIO::TypeInt);
    return !spp || spp->get_int() != p.range->count();
}

}  // namespace

MergedProvenance check_merge_provenance(const Parts& parts, bool allow_partial)
{
    const std::vector<layers::SampleProvenance> all = read_all(parts);
    refuse_overlaps(parts, all);
    MergedProvenance result;

    std::optional<std::size_t> first_task;
    std::vector<std::optional<std::size_t>> holder;  // the part holding each task index
    for (std::size_t k = 0; k < all.size(); ++k) {
        const layers::SampleProvenance& p = all[k];
        if (!p.is_task())
            continue;
        if (!first_task) {
            first_task = k;
            if (*p.task_count > kMaxTasks)
                throw std::invalid_argument(label(parts, k, p) + ": a task count above " +
                                            std::to_string(kMaxTasks) + " is not a farm split");
            holder.resize(std::size_t(*p.task_count));
        }
        const layers::SampleProvenance& t = all[*first_task];
        if (*p.task_count != *t.task_count)
            throw std::invalid_argument(label(parts, k, p) + " and " +
                                        label(parts, *first_task, t) +
                                        " split the frame into different task counts");
        if (p.seed != t.seed)
            throw std::invalid_argument(label(parts, k, p) + " and " +
                                        label(parts, *first_task, t) +
                                        " are tasks of one frame with different seeds");
        auto& slot = holder[std::size_t(*p.task_index)];
        if (slot)
            throw std::invalid_argument(label(parts, *slot, all[*slot]) + " and " +
                                        label(parts, k, p) + " are both task " +
                                        std::to_string(*p.task_index) + "/" +
                                        std::to_string(*p.task_count));
        slot = k;
        if (!p.range || stopped_early(*parts[k], p)) {
            if (!allow_partial)
                throw std::invalid_argument(
                    label(parts, k, p) +
                    " stopped before its last sample: resume it (statmc-render --resume) or "
                    "merge with :allow_partial=1");
            result.partial_tasks.push_back(*p.task_index);
        }
    }
    for (std::size_t i = 0; i < holder.size(); ++i)
        if (!holder[i])
            result.missing_tasks.push_back(int(i));
    if (!result.missing_tasks.empty() && !allow_partial) {
        std::string list;
        for (int i : result.missing_tasks)
            list += (list.empty() ? "" : ", ") + std::to_string(i);
        throw std::invalid_argument(
            "the task set is incomplete: " + std::to_string(result.missing_tasks.size()) + " of " +
            std::to_string(holder.size()) + " tasks missing (task " + list +
            "); give them all, or merge with :allow_partial=1");
    }

    // A complete set holds each task's own share of [0, S): a task file written before its
    // task ended (statmc-render --write-every-iteration) holds less and is no task's share.
    if (first_task && result.missing_tasks.empty() && result.partial_tasks.empty()) {
        int total = 0;
        for (const auto& slot : holder)
            total = std::max(total, all[*slot].range->end);
        const int n = int(holder.size());
        for (int i = 0; i < n; ++i) {
            const layers::SampleRange want{int(std::int64_t(i) * total / n),
                                           int(std::int64_t(i + 1) * total / n)};
            const layers::SampleRange got = *all[*holder[std::size_t(i)]].range;
            if (got.begin != want.begin || got.end != want.end)
                throw std::invalid_argument(
                    "the tasks do not split one frame of " + std::to_string(total) +
                    " samples: " +
                    label(parts, *holder[std::size_t(i)], all[*holder[std::size_t(i)]]) +
                    " holds other samples than task " + std::to_string(i) + "'s share (" +
                    std::to_string(want.begin) + ".." + std::to_string(want.end - 1) +
                    "). A task file written before its task ended (--write-every-iteration), "
                    "or tasks of different --spp?");
        }
    }

    // The merge's own provenance: the common seed, and the sample range when the parts'
    // ranges join into one.
    const bool one_seed = std::all_of(all.begin(), all.end(), [&](const auto& p) {
        return p.seed && p.seed == all[0].seed;
    });
    if (one_seed) {
        result.merged.seed = all[0].seed;
        std::vector<layers::SampleRange> ranges;
        for (const auto& p : all)
            if (p.range)
                ranges.push_back(*p.range);
        std::sort(ranges.begin(), ranges.end(),
                  [](const auto& a, const auto& b) { return a.begin < b.begin; });
        bool joined = ranges.size() == all.size() && result.partial_tasks.empty();
        for (std::size_t i = 1; joined && i < ranges.size(); ++i)
            joined = ranges[i].begin == ranges[i - 1].end;
        if (joined)
            result.merged.range = layers::SampleRange{ranges.front().begin, ranges.back().end};
        else  // a seed without its range would read back as samples [0, spp)
            result.merged.seed.reset();
    }
    return result;
}

}  // namespace statmc
