// An image of per-pixel accumulators: what a renderer adds samples to, tile by tile,
// and what merges exactly across tiles, passes and machines.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

#include "statmc/core/pixel_moments.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

/// Dense float planes of statistics (count, mean, variance, Box-Cox mean, variance, M3/n,
/// and the higher moments M3/n, M4/n and Box-Cox M4/n), the exported form of a
/// StatisticsImage; view() exposes them to the rest of core. Planes a source does not
/// provide (Box-Cox for K passes) are left empty.
struct StatisticsPlanes {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> count;
    std::vector<float> mean, variance, bc_mean, bc_variance, bc_moment3;  // channel-major
    std::vector<float> moment3, moment4, bc_moment4;                      // channel-major

    StatisticsView view() const;
};

/// The accumulator a stored pixel of `view` stands for (M2 = s²(n − 1), Mk = n·mk). Every
/// plane but the count and the mean may be absent: its moments come back as 0, and a
/// merge of such pixels is exact only in the planes present.
template <int C>
PixelMoments<C, double> stored_pixel(const StatisticsView& view, int x, int y);

/// `view` with the untransformed mean and variance standing in for absent Box-Cox planes
/// (and `zero` for M3), so that exact merging runs on images without them; whoever merges
/// drops the stand-ins from the result.
StatisticsView with_stand_in_box_cox(StatisticsView view, const ConstPlane& zero);

template <int C>
class StatisticsImage {
public:
    using Pixel = PixelMoments<C, double>;

    StatisticsImage(int width, int height)
        : width_(width), height_(height), pixels_(std::size_t(width) * height)
    {
        if (width <= 0 || height <= 0)
            throw std::invalid_argument("StatisticsImage: empty resolution");
    }

    int width() const { return width_; }
    int height() const { return height_; }
    Pixel& at(int x, int y) { return pixels_[std::size_t(y) * width_ + x]; }
    const Pixel& at(int x, int y) const { return pixels_[std::size_t(y) * width_ + x]; }

    /// The accumulators as they are in memory, pixel by pixel in scanline order: what a
    /// render checkpoint saves and restores bitwise.
    std::vector<Pixel>& accumulators() { return pixels_; }
    const std::vector<Pixel>& accumulators() const { return pixels_; }

    void add(int x, int y, const float* sample) { at(x, y).add(sample); }
    /// Folds in the statistics of the same frame from another tile set, pass or machine.
    void merge(const StatisticsImage& other)
    {
        if (other.width_ != width_ || other.height_ != height_)
            throw std::invalid_argument("StatisticsImage::merge: resolutions differ");
        for (std::size_t i = 0; i < pixels_.size(); ++i)
            pixels_[i].merge(other.pixels_[i]);
    }

    StatisticsPlanes planes() const;
    /// Rebuilds accumulators from stored planes (M2 = s²(n − 1), Mk = n·mk). Higher moments
    /// the view lacks (a version-1 file) come back as 0.
    static StatisticsImage from_view(const StatisticsView& view);
    /// The exact merge of views of one frame (same resolution, C channels, Box-Cox planes),
    /// each pixel folded in view order: the same result for any `nthreads` (0 = all cores).
    static StatisticsImage merged(const std::vector<StatisticsView>& views, int nthreads = 0);

private:
    int width_;
    int height_;
    std::vector<Pixel> pixels_;
};

extern template class StatisticsImage<1>;
extern template class StatisticsImage<3>;
extern template class StatisticsImage<4>;

}  // namespace statmc
