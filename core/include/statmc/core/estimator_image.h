// Per-pixel estimators ready for the membership test, built from any of the three kinds
// of statistics a renderer can give.
#pragma once

#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "statmc/core/plane.h"
#include "statmc/core/statistics_view.h"

namespace statmc {

/// The most channels an estimator image (and the filter) holds: four, or up to four
/// three-channel layers side by side, which joint AOV denoising tests together.
inline constexpr int kMaxEstimatorChannels = 12;

/// Which samples the test compares.
enum class TestDomain {
    BoxCox,         ///< Box-Cox (λ = ½) with Johnson's skewness correction: StatMC proper
    Untransformed,  ///< the plain means, as a variance AOV or Moon et al.'s test allows
};

/// What the filter needs of each pixel: the value it averages (the untransformed mean),
/// the quantity it tests (test_mean) with the variance of that estimate, and the sample
/// count that sets the degrees of freedom. All planes are dense and channel-major.
///
/// A pixel is *testable* when count ≥ 2 and its test mean and variance are finite with
/// variance ≥ 0. An untestable pixel keeps its own value and is nobody's member; a
/// non-finite value is stored as 0 (the rule §2 applies to samples).
struct EstimatorImage {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> count;
    std::vector<float> value;
    std::vector<float> test_mean;
    std::vector<float> test_variance;
    /// The domain of test_mean and test_variance. Only Box-Cox variances are steady enough
    /// across brightness for the firefly guard (firefly_guard.h) to compare them.
    TestDomain domain = TestDomain::Untransformed;
    /// How many of the last channels are context channels (context_channel.h): they take
    /// part in the test only. The firefly guard's noise levels leave them out, since a box
    /// that holds a firefly would otherwise raise its neighbours' levels, and with them
    /// what they accept.
    int context_channels = 0;
    /// Per pixel, how many samples' worth its value rests on: for its brightest channel,
    /// the effective count (Σx)²/Σx² = n·m²/(m² + s²(n − 1)/n) of the samples' values
    /// themselves, ≈ n for an even pixel, ≈ k for k bright hits among misses, ≈ 1 for a
    /// single outlier (a firefly). Empty where the statistics have no untransformed
    /// variance. The firefly guard reads it (firefly_guard.h).
    std::vector<float> support;

    EstimatorImage() = default;
    EstimatorImage(int width, int height, int channels);

    std::size_t pixels() const { return std::size_t(width) * height; }
    std::size_t index(int c, int x, int y) const
    {
        return std::size_t(c) * pixels() + std::size_t(y) * width + x;
    }
    /// One channel's part of testable(): a finite mean and a finite, non-negative variance.
    /// Branch-free (|v| ≤ FLT_MAX is std::isfinite(v)), so that testable_row vectorises.
    static bool testable_estimate(float mean, float variance)
    {
        return bool(int(std::abs(mean) <= FLT_MAX) & int(std::abs(variance) <= FLT_MAX) &
                    int(variance >= 0));
    }
    bool testable(int x, int y) const
    {
        if (!(count[index(0, x, y)] >= 2))
            return false;
        for (int c = 0; c < channels; ++c)
            if (!testable_estimate(test_mean[index(c, x, y)], test_variance[index(c, x, y)]))
                return false;
        return true;
    }
    /// testable(x, y) for the whole of row y, as 1 or 0 in out[0, width): plane by plane
    /// and branch-free, so that it vectorises. The filter's layout and the firefly guard
    /// ask it of every pixel.
    void testable_row(int y, std::uint8_t* out) const;
};

/// Full statistics (mode 1) or mean + variance + count (mode 2, TestDomain::Untransformed).
/// Throws std::invalid_argument when the view lacks the planes the domain needs.
EstimatorImage estimators_from_statistics(const StatisticsView& stats, TestDomain domain);

/// The channels of `parts` side by side (parts[0]'s first), as one image: a filter over it
/// accepts a neighbour only where every part's test does, and averages every channel with
/// the same weights. The parts must match in size and domain and share their counts, and
/// hold at most kMaxEstimatorChannels channels together and have no context channels;
/// else std::invalid_argument.
EstimatorImage side_by_side(const std::vector<const EstimatorImage*>& parts);

}  // namespace statmc
