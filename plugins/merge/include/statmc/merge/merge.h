// The merge operator in the style of OIIO's ImageBufAlgo: statistics images of the same
// frame accumulated separately (render-farm tasks with different seeds) in, the one
// image an all-at-once render would have written out.
#pragma once

#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc {

struct MergeOptions {
    /// Merge an incomplete farm task set (tasks missing or stopped early): the result holds
    /// the samples given and says how many tasks were missing (statmc:tasksMissing).
    bool allow_partial = false;
};

/// Merges the beauty statistics of `parts` exactly (core's StatisticsImage::merge: counts
/// add, means and M2/M3 combine by Chan et al. / Pébay), so that the result equals the
/// statistics of all their samples up to float rounding. Images without the Box-Cox
/// layers (a renderer's variance AOV) merge their means and variances. Albedo, normal and
/// depth guides are carried as sample-weighted means; other channels (per-bounce AOVs) are
/// dropped. `statmc:spp` is the sum of the parts' (when all have it); `statmc:seed` and the
/// sample range are kept when the parts share the seed and their ranges join.
///
/// The parts must number at least 2 (1 with allow_partial) and share resolution, data
/// window, channel names and statmc:formatVersion; none may be denoised (`statmc:denoised`
/// = 1): merging denoised means would count neighbours' samples as this pixel's. Samples
/// counted twice and inconsistent or incomplete task sets are refused
/// (check_merge_provenance). `dst` is float with the parts' data window.
///
/// Returns false after `dst.errorfmt(...)` naming the offending parts (by index and
/// ImageBuf name, i.e. file); never throws.
bool merge(OIIO::ImageBuf& dst, const std::vector<const OIIO::ImageBuf*>& parts,
           const MergeOptions& options = {}, int nthreads = 0);

/// The return-value form: check `has_error()` on the result.
OIIO::ImageBuf merge(const std::vector<const OIIO::ImageBuf*>& parts,
                     const MergeOptions& options = {}, int nthreads = 0);

}  // namespace statmc
