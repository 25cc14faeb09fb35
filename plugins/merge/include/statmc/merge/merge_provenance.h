// Which samples a merge would combine (docs/farm.md): parts holding the same samples twice,
// and farm task sets that are inconsistent or incomplete, are refused before any pixel is
// read, with a message naming the parts.
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/sample_provenance.h"

namespace statmc {

struct MergedProvenance {
    layers::SampleProvenance merged;  ///< what the result's header says (no task fields)
    std::vector<int> missing_tasks;   ///< with allow_partial: the task indices not given
    std::vector<int> partial_tasks;   ///< with allow_partial: tasks that stopped early
};

/// Checks the provenance of `parts` (statmc:seed, statmc:sampleBegin/End, statmc:taskIndex/
/// taskCount, statmc:spp) and returns the merge's. Throws std::invalid_argument, naming the
/// parts by index and file, when
/// - two parts with the same seed hold overlapping sample ranges (those samples would count
///   twice);
/// - tasks disagree on the task count or seed, or one task index is given twice;
/// - and, unless `allow_partial`: a task index is missing, or a task stopped early (its
///   sample count is short of its range).
/// Parts without a seed (another renderer's passes) are not checked for overlap.
MergedProvenance check_merge_provenance(const std::vector<const OIIO::ImageBuf*>& parts,
                                        bool allow_partial);

}  // namespace statmc
