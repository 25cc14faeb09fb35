// Joint AOVs (docs/method.md §14): which statistics decide their one membership, found
// once per run.
#pragma once

#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/estimator_image.h"
#include "statmc/denoise/denoise_image_options.h"
#include "statmc/layers/statistics_layers.h"

namespace statmc::denoising {

struct JointAovs {
    /// Every AOV's test decides beside the lead's: each has the test's statistics.
    bool side_by_side = false;
    std::string note;  ///< why the lead's test decides alone, where an AOV lacks them
    /// Each listed AOV's channels: as found, then as the run reads them (check_joint_aovs).
    std::vector<layers::StatisticsChannels> channels;
};

/// The listed AOVs of a joint run (none without `opt.joint`), each with the lead's
/// channel count (else a LayerError).
JointAovs plan_joint_aovs(const OIIO::ImageSpec& spec, const layers::StatisticsChannels& lead,
                          TestDomain domain, const DenoiseImageOptions& opt);
/// Narrows each AOV's channels to what the run reads (its test's statistics side by side,
/// else its means) and validates them over `region`.
void check_joint_aovs(const OIIO::ImageBuf& in, JointAovs& joint, TestDomain domain,
                      const DenoiseImageOptions& opt, const OIIO::ROI& region);

}  // namespace statmc::denoising
