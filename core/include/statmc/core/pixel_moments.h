// The per-pixel statistics of docs/method.md §2 for C channels: count, untransformed and
// Box-Cox moments, updated one sample at a time and merged exactly.
#pragma once

#include "statmc/core/box_cox.h"
#include "statmc/core/moments.h"

namespace statmc {

template <int C, class Real = double>
struct PixelMoments {
    static_assert(C >= 1 && C <= 4, "1 to 4 channels");
    static constexpr int kChannels = C;

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

    void merge(const PixelMoments& other)
    {
        for (int c = 0; c < C; ++c) {
            raw[c].merge(n, other.raw[c], other.n);
            box_cox[c].merge(n, other.box_cox[c], other.n);
        }
        n += other.n;
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
