// The renderer's output: the film's statistics and guides under the EXR layer contract
// (built by layers/, never by hand), plus the render's own header attributes.
#pragma once

#include <optional>
#include <string>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/sample_provenance.h"
#include "statmc/render/render_loop.h"

namespace statmc::render {

struct OutputInfo {
    /// The per-pixel sample counts: statmc:spp when uniform, else statmc:sppMin and
    /// statmc:sppMean (an interrupted render), so that no header claims a count it lacks.
    Film::SampleCounts spp;
    /// statmc:seed, the sample range and the farm task (layers/sample_provenance.h).
    layers::SampleProvenance provenance;
    float render_seconds = 0;
    std::string scene;
    std::optional<int> frame;  ///< statmc:frame, in a sequence
    /// Also write M3, M4 and boxcoxM4 (format version 2's higher moments). No stage of
    /// statmc reads them; they merge exactly, for research on the variance's own statistics.
    bool higher_moments = false;
};

/// Mean, variance, Box-Cox statistics, sampleCount, the per-bounce AOVs the film tracks
/// (bounce<j>L, bounce<j>LightWins, bounce<j>BsdfWins), albedo, normal and depth.
OIIO::ImageBuf make_output_image(const Film& film, const OutputInfo& info);

/// Writes `image` as OpenEXR under the contract's storage rules through
/// layers::write_image_file (a temporary file renamed into place, so that a failed or
/// interrupted write never leaves a partial file). Throws layers::FileError.
void write_exr(const OIIO::ImageBuf& image, const std::string& path);

/// Where --denoise writes: "out.exr" -> "out.denoised.exr".
std::string denoised_path(const std::string& path);

}  // namespace statmc::render
