// The variance filter's disk loop across W consecutive pixels of a row, written once with
// GCC's vector extensions and compiled per instruction set (variance_filter_avx2.cpp,
// variance_filter_avx512.cpp). Each lane computes exactly what the scalar loop in
// variance_filter.cpp computes for its pixel: the same double products and sums in the
// same tap order, no fused multiply-add (those files build with -ffp-contract=off), and the
// guide weight's exp by the same std::exp, lane by lane. So the output's bits do not depend
// on the level.
//
// Internal linkage on purpose: the header is compiled once per instruction set.
#pragma once

#include <cmath>
#include <cstring>
#include <vector>

#include "variance_filter_layout.h"

namespace statmc::detail {
namespace {

// GCC ignores vector_size on a type that depends on a template parameter, so the two
// widths are spelled out.
typedef double Double4 __attribute__((vector_size(32)));
typedef float Float4 __attribute__((vector_size(16)));
typedef double Double8 __attribute__((vector_size(64)));
typedef float Float8 __attribute__((vector_size(32)));

template <int W>
struct VectorTypes;
template <>
struct VectorTypes<4> {
    using D = Double4;
    using Fl = Float4;
};
template <>
struct VectorTypes<8> {
    using D = Double8;
    using Fl = Float8;
};

template <int W>
struct Lanes {
    using D = typename VectorTypes<W>::D;
    using Mask = decltype(D{} < D{});  // all ones where true
    using Fl = typename VectorTypes<W>::Fl;

    static D splat(double x)
    {
        D v;
        for (int k = 0; k < W; ++k)
            v[k] = x;
        return v;
    }
    static D load(const double* p)
    {
        D v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    static D load(const float* p)
    {
        Fl v;
        std::memcpy(&v, p, sizeof v);
        return __builtin_convertvector(v, D);
    }
    static bool any(Mask m)
    {
        for (int k = 0; k < W; ++k)
            if (m[k])
                return true;
        return false;
    }
};

// One channel of add_variance_disk: `weights` holds each tap's W guide weights, or is null
// (the spatial weight alone). Borrowers gather their neighbours' s² (lends() in
// variance_filter.cpp); TestMeans: the prior takes only neighbours that pass the test on
// the means (in_prior()).
template <int W, bool TestMeans>
void add_variance_channel(const VarianceLayout& L, int c, std::size_t p0, const double* weights,
                          VarianceSums* sums)
{
    using V = Lanes<W>;
    using D = typename V::D;
    using Mask = typename V::Mask;
    const std::size_t plane = std::size_t(c) * L.pixels;
    const D prior_z2 = V::splat(L.prior_z2);
    const D centre = V::load(L.lend_s2.data() + plane + p0);
    D mean{}, mean_se2{};
    if (TestMeans) {
        mean = V::load(L.mean.data() + plane + p0);
        mean_se2 = V::load(L.mean_se2.data() + plane + p0);
    }
    // Lanes without an estimate that take any neighbour with one: most chunks have none.
    const Mask borrows = L.borrow ? centre != centre : Mask{};
    const bool gathers = V::any(borrows);
    D sum, weight, prior_sum, prior_weight;
    for (int k = 0; k < W; ++k) {
        sum[k] = sums[k].sum[c];
        weight[k] = sums[k].weight[c];
        prior_sum[k] = sums[k].prior_sum[c];
        prior_weight[k] = sums[k].prior_weight[c];
    }
    for (std::size_t t = 0; t < L.taps.size(); ++t) {
        const VarianceTap& tap = L.taps[t];
        const std::size_t q0 = plane + p0 + std::ptrdiff_t(tap.dy) * L.width + tap.dx;
        const D w = weights ? V::load(weights + t * W) : V::splat(tap.spatial);
        if (gathers) {
            const D lend_s2 = V::load(L.lend_s2.data() + q0);
            const Mask member = borrows & (lend_s2 == lend_s2);
            sum = member ? sum + w * lend_s2 : sum;
            weight = member ? weight + w : weight;
        }
        const D prior_s2 = V::load(L.prior_s2.data() + q0);
        Mask usable = prior_s2 == prior_s2;
        if (TestMeans) {
            const D d = mean - V::load(L.mean.data() + q0);
            usable = usable & (d * d <= prior_z2 * (mean_se2 + V::load(L.mean_se2.data() + q0)));
        }
        prior_sum = usable ? prior_sum + w * prior_s2 : prior_sum;
        prior_weight = usable ? prior_weight + w : prior_weight;
    }
    for (int k = 0; k < W; ++k) {
        sums[k].sum[c] = sum[k];
        sums[k].weight[c] = weight[k];
        sums[k].prior_sum[c] = prior_sum[k];
        sums[k].prior_weight[c] = prior_weight[k];
    }
}

template <int W>
void add_variance_disk(const VarianceLayout& L, int x0, int y, VarianceSums* sums)
{
    using V = Lanes<W>;
    using D = typename V::D;
    const int channels = L.channels, groups = L.guide_groups();
    const std::size_t p0 = std::size_t(y) * L.width + x0;
    // The guides' weights of every tap first, then the taps: a call to std::exp inside the
    // tap loop would spill every live vector around it (they are all caller-saved).
    thread_local std::vector<double> weights;
    if (groups > 0) {
        weights.resize(L.taps.size() * W);
        D guide[6];
        for (int g = 0; g < 3 * groups; ++g)
            guide[g] = V::load(L.guide[g] + p0);
        for (std::size_t t = 0; t < L.taps.size(); ++t) {
            const std::size_t q0 = p0 + std::ptrdiff_t(L.taps[t].dy) * L.width + L.taps[t].dx;
            D exponent = V::splat(0.0);
            for (int group = 0; group < groups; ++group) {
                D d2 = V::splat(0.0);
                for (int k = 0; k < 3; ++k) {
                    const D d = guide[3 * group + k] - V::load(L.guide[3 * group + k] + q0);
                    d2 = d2 + d * d;
                }
                exponent = exponent + d2 * V::splat(L.guide_falloff[group]);
            }
            std::memcpy(weights.data() + t * W, &exponent, sizeof exponent);
        }
        for (std::size_t t = 0; t < L.taps.size(); ++t)
            for (int k = 0; k < W; ++k) {
                double& w = weights[t * W + k];
                w = guide_weight(L.taps[t].spatial, w);
            }
    }

    // Channel by channel, each walking every tap: one channel's sums and centre values fit
    // in registers (three channels' at once do not), and each sum still adds its taps in
    // raster order.
    const double* w = groups > 0 ? weights.data() : nullptr;
    for (int c = 0; c < channels; ++c) {
        if (L.prior_z2 > 0)
            add_variance_channel<W, true>(L, c, p0, w, sums);
        else
            add_variance_channel<W, false>(L, c, p0, w, sums);
    }
}

}  // namespace
}  // namespace statmc::detail
