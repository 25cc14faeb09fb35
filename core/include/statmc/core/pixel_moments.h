// The per-pixel statistics of docs/method.md §2 for C channels: count, untransformed and
// Box-Cox moments, updated one sample at a time and merged exactly.
#pragma once

#include "statmc/core/box_cox.h"
#include "statmc/core/moments.h"
#include "statmc/core/position_moments.h"

namespace statmc {

template <int C, class Real = double>
struct PixelMoments {
    static_assert(C >= 1 && C <= 4, "1 to 4 channels");
    static constexpr int kChannels = C;
    using Position = PositionMoments<C, Real>;

    Real n = 0;
    CentralMoments<Real> raw[C];      ///< untransformed samples (the image and its variance)
    CentralMoments<Real> box_cox[C];  ///< Box-Cox transformed samples (what the test uses)

    /// Adds one Monte Carlo sample; an unusable one (NaN, Inf, negative) counts as 0.
    void add(const float* sample)
    {
        Real x[C], b[C];
        values_of(sample, x, b);
        add_values(x, b);
    }

    /// add() for a sample taken at sub-pixel offset (u, v), with its position co-moments.
    void add(const float* sample, Real u, Real v, Position& position)
    {
        Real x[C], b[C], raw_mean[C], bc_mean[C];
        values_of(sample, x, b);
        for (int c = 0; c < C; ++c) {
            raw_mean[c] = raw[c].mean;
            bc_mean[c] = box_cox[c].mean;
        }
        position.add(n, u, v, x, raw_mean, b, bc_mean);
        add_values(x, b);
    }

    void merge(const PixelMoments& other)
    {
        for (int c = 0; c < C; ++c) {
            raw[c].merge(n, other.raw[c], other.n);
            box_cox[c].merge(n, other.box_cox[c], other.n);
        }
        n += other.n;
    }

    /// merge() with the position co-moments of both sets.
    void merge(const PixelMoments& other, Position& position, const Position& other_position)
    {
        Real delta_raw[C], delta_bc[C];
        for (int c = 0; c < C; ++c) {
            delta_raw[c] = other.raw[c].mean - raw[c].mean;
            delta_bc[c] = other.box_cox[c].mean - box_cox[c].mean;
        }
        position.merge(n, other_position, other.n, delta_raw, delta_bc);
        merge(other);
    }

private:
    static void values_of(const float* sample, Real* x, Real* b)
    {
        const bool usable = sample_is_usable(sample, C);
        for (int c = 0; c < C; ++c) {
            x[c] = usable ? Real(sample[c]) : Real(0);
            b[c] = statmc::box_cox(x[c]);
        }
    }
    void add_values(const Real* x, const Real* b)
    {
        for (int c = 0; c < C; ++c) {
            raw[c].add(n, x[c]);
            box_cox[c].add(n, b[c]);
        }
        n += 1;
    }
};

}  // namespace statmc
