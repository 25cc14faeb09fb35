// Temporal members (docs/method.md §13): a pixel of a neighbouring frame is one more
// estimator of the centre pixel's expectation. Where the t-test cannot tell the two apart,
// its samples are merged exactly into the centre's statistics, as if the frame had been
// rendered with more samples; everything downstream (the filter, its guards, the ICI
// ladder) then reads the merged statistics. Where the test tells them apart (the scene
// moved, the motion vectors are wrong, a highlight crawled), nothing is merged: the same
// test that decides spatial membership guards against ghosting.
#pragma once

#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/plane.h"
#include "statmc/core/statistics_image.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

/// One frame of a sequence: its statistics and, optionally, its motion: per pixel, the
/// screen-space offset in pixels from where the pixel's first hit is in this frame to
/// where it was in the previous frame (layer motion.X/Y, docs/exr-layers.md).
struct TemporalFrame {
    StatisticsView stats;
    ConstPlane motion_x, motion_y;  ///< both null: a static camera and scene

    bool has_motion() const { return motion_x && motion_y; }
};

struct TemporalOptions {
    int frames = 0;  ///< K: frames t−K … t+K are candidates; 0 = off
    /// Besides the corresponding pixel, the pixels within this radius of it in each
    /// neighbouring frame are candidates too; 0 = the corresponding pixel only.
    int radius = 0;

    /// Empty when valid, else a message naming the offending parameter.
    std::string validate() const;
};

/// Where pixel (x, y) of frame `centre` is in frame `other`, following the motion layers
/// frame by frame (docs/method.md §13); false when it leaves the image, when the forward
/// search does not land back on the pixel (a disocclusion), or when `other` is `centre`.
/// Frames without motion correspond pixel for pixel.
bool corresponding_pixel(const std::vector<TemporalFrame>& frames, int centre, int other, int x,
                         int y, int& ox, int& oy);

/// The statistics of frame `centre` of `frames` (consecutive frames in time order, all of
/// one resolution and channel count, every one with motion or none) with the members of
/// the other frames merged in. A candidate joins when both pixels are testable, the
/// firefly guard (filter.firefly_ratio, Box-Cox only) lets it in, and the test at
/// filter.alpha in `domain` passes in every channel. Candidates are merged in frame order,
/// then row-major within the disk: the result is bitwise the same for any thread count.
/// Without Box-Cox planes (the untransformed domain), the result has none either.
/// `members`, when given (centre's width), receives the temporal members per pixel.
/// Throws std::invalid_argument for mismatched frames or bad options.
StatisticsPlanes merge_temporal_members(const std::vector<TemporalFrame>& frames, int centre,
                                        TestDomain domain, const TemporalOptions& temporal,
                                        const DenoiseOptions& filter, int nthreads = 0,
                                        Plane members = {});

}  // namespace statmc
