// Statistics from K independent renders of one frame: how any renderer can use statmc
// without integration: each render is one sample of every pixel (docs/exr-layers.md,
// "Three kinds of input").
#pragma once

#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_image.h"

namespace statmc {

/// Treats each of K ≥ 2 renders (different seeds) as one sample of the pixel: count = K,
/// mean = the mean of the renders, variance = their sample variance (per render), the
/// higher moments M3/K and M4/K of the renders about their mean, no Box-Cox planes. Tested
/// untransformed this gives df = 2K − 2. `passes[k][c]` is channel c of render k; a render pixel
/// that is non-finite or has negative luminance counts as 0 in every channel, as a broken sample
/// would (box_cox.h, sample_is_usable). Throws std::invalid_argument for K < 2 or renders that
/// differ in channel count.
StatisticsPlanes statistics_from_passes(const std::vector<std::vector<ConstPlane>>& passes,
                                        int width, int height);

}  // namespace statmc
