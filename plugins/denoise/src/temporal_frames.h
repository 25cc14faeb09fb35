// Frame sequences (docs/method.md §13): the centre's statistics with the members its
// neighbours offer merged in, every neighbour checked to be the same frame, with the same
// statistics and its own samples.
#pragma once

#include <OpenImageIO/imagebuf.h>

#include "statmc/core/estimator_image.h"
#include "statmc/core/statistics_image.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/statistics_layers.h"

namespace statmc::denoising {

/// The centre's statistics with the members of its neighbours merged in, over the whole
/// data window (a member's correspondence may lie anywhere in it).
StatisticsPlanes merged_over_time(const OIIO::ImageBuf& in, const layers::StatisticsChannels& ch,
                                  TestDomain domain, const FrameNeighbours& neighbours,
                                  const DenoiseImageOptions& opt, int nthreads);
/// `shape` (the planes the stages read) with each plane taken from `values`.
StatisticsView with_planes_of(StatisticsView shape, const StatisticsView& values);

}  // namespace statmc::denoising
