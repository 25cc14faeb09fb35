// Where a statistics image's samples came from: the seed, the range of sample indices each
// pixel's stream drew, and the farm task. statmc-render writes it; merge reads it to refuse
// samples counted twice and incomplete task sets (docs/farm.md).
#pragma once

#include <optional>
#include <string>

#include <OpenImageIO/imageio.h>

namespace statmc::layers {

/// Sample indices [begin, end) of every pixel's stream.
struct SampleRange {
    int begin = 0, end = 0;
    int count() const { return end - begin; }
    bool overlaps(const SampleRange& other) const { return begin < other.end && other.begin < end; }
};

struct SampleProvenance {
    std::optional<int> seed;                    ///< statmc:seed
    std::optional<SampleRange> range;           ///< statmc:sampleBegin/End; else [0, statmc:spp)
    std::optional<int> task_index, task_count;  ///< statmc:taskIndex/taskCount

    bool is_task() const { return task_count.has_value(); }
};

/// Reads the attributes of `spec`. A render that predates the range attributes but has
/// statmc:spp drew samples [0, spp): that is its range. Throws LayerError naming the
/// attribute when the values contradict each other (end before begin, a task index out of
/// 0..count-1, only one of a pair).
SampleProvenance read_sample_provenance(const OIIO::ImageSpec& spec);

/// Writes the attributes that `provenance` has; leaves the others alone.
void write_sample_provenance(OIIO::ImageSpec& spec, const SampleProvenance& provenance);

/// The seed of frame `frame` of a sequence rendered with `seed` (statmc-render --frames,
/// statmc-farm): `seed` for frame 0, and a different non-negative seed for every other frame
/// (an odd multiplier is one-to-one modulo 2^31), so the frames' samples are independent and
/// their provenance says so.
int frame_seed(int seed, int frame);

/// Whether `a` and `b` drew some of the same samples: one seed and overlapping ranges.
bool shares_samples(const SampleProvenance& a, const SampleProvenance& b);

/// "seed 3, samples 0..63, task 2/4" (what an error message calls an input).
std::string describe(const SampleProvenance& provenance);

}  // namespace statmc::layers
