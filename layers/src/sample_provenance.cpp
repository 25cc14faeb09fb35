#include "statmc/layers/sample_provenance.h"

#include <cstdint>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_names.h"

namespace statmc::layers {

namespace {

std::optional<int> int_attribute(const OIIO::ImageSpec& spec, const char* name)
{
    const OIIO::ParamValue* p = spec.find_attribute(name);
    if (!p)
        return std::nullopt;
    if (p->type() != OIIO::TypeInt)
        throw LayerError(std::string(name) + " must be an int, got " + p->type().c_str());
    return p->get_int();
}

// Both of a pair or neither.
void require_pair(const std::optional<int>& a, const char* a_name, const std::optional<int>& b,
                  const char* b_name)
{
    if (a.has_value() != b.has_value())
        throw LayerError(std::string(a ? a_name : b_name) + " is set but " + (a ? b_name : a_name) +
                         " is not");
}

}  // namespace

SampleProvenance read_sample_provenance(const OIIO::ImageSpec& spec)
{
    SampleProvenance p;
    p.seed = int_attribute(spec, attr::kSeed);
    const auto begin = int_attribute(spec, attr::kSampleBegin),
               end = int_attribute(spec, attr::kSampleEnd);
    require_pair(begin, attr::kSampleBegin, end, attr::kSampleEnd);
    if (begin) {
        if (*begin < 0 || *end < *begin)
            throw LayerError(std::string(attr::kSampleBegin) + ".." + attr::kSampleEnd + " is " +
                             std::to_string(*begin) + ".." + std::to_string(*end) +
                             ", not a range of sample indices");
        p.range = SampleRange{*begin, *end};
    } else if (const auto spp = int_attribute(spec, attr::kSpp)) {
        p.range = SampleRange{0, *spp};
    }
    p.task_index = int_attribute(spec, attr::kTaskIndex);
    p.task_count = int_attribute(spec, attr::kTaskCount);
    require_pair(p.task_index, attr::kTaskIndex, p.task_count, attr::kTaskCount);
    if (p.task_count && (*p.task_count < 1 || *p.task_index < 0 || *p.task_index >= *p.task_count))
        throw LayerError("task " + std::to_string(*p.task_index) + " of " +
                         std::to_string(*p.task_count) + " (" + attr::kTaskIndex + ", " +
                         attr::kTaskCount + ") is not a task: the index must be in 0..count-1");
    return p;
}

void write_sample_provenance(OIIO::ImageSpec& spec, const SampleProvenance& p)
{
    if (p.seed)
        spec.attribute(attr::kSeed, *p.seed);
    if (p.range) {
        spec.attribute(attr::kSampleBegin, p.range->begin);
        spec.attribute(attr::kSampleEnd, p.range->end);
    }
    if (p.task_count) {
        spec.attribute(attr::kTaskIndex, *p.task_index);
        spec.attribute(attr::kTaskCount, *p.task_count);
    }
}

int frame_seed(int seed, int frame)
{
    const std::uint32_t mixed = std::uint32_t(seed) ^ (std::uint32_t(frame) * 0x9E3779B1u);
    return int(mixed & 0x7fffffffu);
}

bool shares_samples(const SampleProvenance& a, const SampleProvenance& b)
{
    return a.seed && b.seed && *a.seed == *b.seed && a.range && b.range &&
           a.range->overlaps(*b.range);
}

std::string describe(const SampleProvenance& p)
{
    std::string text = p.seed ? "seed " + std::to_string(*p.seed) : "no seed";
    if (p.range)
        text += ", samples " + std::to_string(p.range->begin) + ".." +
                std::to_string(p.range->end - 1);
    if (p.task_count)
        text += ", task " + std::to_string(*p.task_index) + "/" + std::to_string(*p.task_count);
    return text;
}

}  // namespace statmc::layers
