// The filter's inner loop, written once over a SIMD type V (simd_scalar.h, simd_avx2.h).
// Lanes are consecutive output pixels of one row; every tap is two unaligned loads per
// tested channel, so the window walk is pure streaming arithmetic.
//
// Everything here has internal linkage on purpose: the header is compiled once per
// instruction set, and shared inline symbols could let the linker mix the two builds.
#pragma once

#include <algorithm>

#include "filter_layout.h"
#include "simd_exp2.h"

namespace statmc::detail {
namespace {

template <class V, int NC>
struct Centre {
    typename V::F mean[NC], threshold[NC];
    typename V::F noise_limit;
};

/// Lanes' membership of the neighbour at offset `off`: all channels pass
/// (μ̃_i − μ̃_j)² − T_j ≤ T_i. This is the fast form of method.md §4,
/// (μ̃_i − μ̃_j)² ≤ γ_i²v_i + γ_j²v_j, kept in difference form: expanding it into
/// D_i + D_j ≤ 2μ̃_iμ̃_j cancels catastrophically in float once v ≪ μ̃² (high spp).
template <class V, int NC, bool kGuard>
inline typename V::M members(const FilterLayout& L, const Centre<V, NC>& ctr, std::ptrdiff_t off)
{
    auto excess = [&](int c) {
        const auto d = V::sub(ctr.mean[c], V::load(L.mean[c] + off));
        return V::fmsub(d, d, V::load(L.threshold[c] + off));
    };
    typename V::M m;
    if constexpr (kGuard) {  // the firefly guard starts the mask chain
        m = V::le(V::load(L.noise + off), ctr.noise_limit);
        m = V::le_and(m, excess(0), ctr.threshold[0]);
    } else {
        m = V::le(excess(0), ctr.threshold[0]);
    }
    for (int c = 1; c < NC; ++c)
        m = V::le_and(m, excess(c), ctr.threshold[c]);
    return m;
}

/// What a chunk of lanes has gathered so far; carried from one band of rows to the next.
template <class V, int NC>
struct Partial {
    typename V::F acc[NC];  // Σ W_ij (F_j − F_i)
    typename V::F weight_sum;
    typename V::F member_count;
    typename V::F inverse_sum;  // Σ W_ij² / n_j, for the effective sample count
};

/// Adds the taps of window rows [dy0, dy1] to the chunk of lanes starting at (x0, y).
template <class V, int NC, int NG, bool kDiagnostics, bool kGuard>
void add_band(const FilterLayout& L, int y, int x0, int dy0, int dy1, Partial<V, NC>& partial)
{
    using F = typename V::F;
    const std::ptrdiff_t centre = std::ptrdiff_t(y) * L.stride + x0;
    Centre<V, NC> ctr;
    // Σ W_ij (F_j − F_i) rather than Σ W_ij F_j: out_i = F_i + that / Σ W_ij is the same
    // average, but members equal to the centre add exactly nothing, so flat regions come
    // back bit for bit and large offsets (HDR) lose no digits.
    F value[NC], acc[NC];
    for (int c = 0; c < NC; ++c) {
        ctr.mean[c] = V::load(L.mean[c] + centre);
        ctr.threshold[c] = V::load(L.threshold[c] + centre);
        value[c] = V::load(L.value[c] + centre);
        acc[c] = partial.acc[c];
    }
    if constexpr (kGuard)
        ctr.noise_limit = V::load(L.noise_limit + centre);
    F guide[NG > 0 ? NG : 1];
    for (int g = 0; g < NG; ++g)
        guide[g] = V::load(L.guide[g] + centre);
    F weight_sum = partial.weight_sum;
    F member_count = partial.member_count;
    F inverse_sum = partial.inverse_sum;

    auto tap = [&](int dx, int dy) {
        const std::ptrdiff_t off = centre + std::ptrdiff_t(dy) * L.stride + dx;
        const auto m = members<V, NC, kGuard>(L, ctr, off);
        if constexpr (NG > 0) {
            // The guide weight costs an exp; a tap no lane accepts adds nothing anyway.
            if (V::none(m))
                return;
        }
        F w;
        if constexpr (NG == 0) {
            w = V::set1(L.spatial(dx, dy));
        } else {
            // log2 w = spatial − Σ (Δg)² (guides are stored pre-scaled), summed as two
            // chains joined at the end: the weight's latency bounds this loop.
            auto difference = [&](int g) { return V::sub(guide[g], V::load(L.guide[g] + off)); };
            constexpr int kHalf = (NG + 1) / 2;
            F near = V::set1(L.spatial_log2(dx, dy));
            for (int g = 0; g < kHalf; ++g) {
                const F d = difference(g);
                near = V::fnmadd(d, d, near);
            }
            F far = V::zero();
            for (int g = kHalf; g < NG; ++g) {
                const F d = difference(g);
                far = g == kHalf ? V::mul(d, d) : V::fmadd(d, d, far);
            }
            w = simd::exp2_nonpositive<V>(V::sub(near, far));
        }
        for (int c = 0; c < NC; ++c)
            acc[c] = V::masked_fmadd(m, w, V::sub(V::load(L.value[c] + off), value[c]), acc[c]);
        weight_sum = V::masked_add(m, weight_sum, w);
        if constexpr (kDiagnostics) {
            member_count = V::masked_add(m, member_count, V::set1(1.f));
            inverse_sum = V::masked_fmadd(m, V::mul(w, w), V::load(L.inverse_count + off), inverse_sum);
        }
    };

    for (int dy = dy0; dy <= dy1; ++dy) {
        const int hw = L.half_width[dy + L.pad_y];
        if (dy != 0) {
            for (int dx = -hw; dx <= hw; ++dx)
                tap(dx, dy);
        } else {  // the centre is in already, with weight 1
            for (int dx = -hw; dx < 0; ++dx)
                tap(dx, 0);
            for (int dx = 1; dx <= hw; ++dx)
                tap(dx, 0);
        }
    }
    for (int c = 0; c < NC; ++c)
        partial.acc[c] = acc[c];
    partial.weight_sum = weight_sum;
    partial.member_count = member_count;
    partial.inverse_sum = inverse_sum;
}

template <class V, int NC, bool kDiagnostics>
void write_chunk(const FilterLayout& L, const std::vector<Plane>& out, const FilterDiagnostics& diag,
                 int y, int x0, const Partial<V, NC>& partial)
{
    const std::ptrdiff_t centre = std::ptrdiff_t(y) * L.stride + x0;
    float lanes[NC][V::kWidth], wsum[V::kWidth], count[V::kWidth], inverse[V::kWidth];
    for (int c = 0; c < NC; ++c)
        V::store(lanes[c], V::add(V::load(L.value[c] + centre), V::div(partial.acc[c], partial.weight_sum)));
    V::store(wsum, partial.weight_sum);
    V::store(count, partial.member_count);
    if constexpr (kDiagnostics)
        V::store(inverse, partial.inverse_sum);
    const int n = std::min(V::kWidth, L.width - x0);
    for (int k = 0; k < n; ++k) {
        for (int c = 0; c < NC; ++c)
            out[c](x0 + k, y) = lanes[c][k];
        if constexpr (kDiagnostics) {
            if (diag.members)
                diag.members(x0 + k, y) = count[k];
            if (diag.weight_sum)
                diag.weight_sum(x0 + k, y) = wsum[k];
            if (diag.effective_samples)
                diag.effective_samples(x0 + k, y) =
                    inverse[k] > 0 ? wsum[k] * wsum[k] / inverse[k] : 0.f;
        }
    }
}

/// Window rows per band. A band of rows across a 64-pixel tile is ~15 KB of planes, so
/// every chunk of the tile reads it from L1; walking each chunk's whole window instead
/// (~70 KB at r = 20) streams it from L2 and runs at half the speed.
constexpr int kBandRows = 4;

template <class V, int NC, int NG, bool kDiagnostics>
void filter_rows_impl(const FilterLayout& L, const std::vector<Plane>& out,
                      const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    std::vector<Partial<V, NC>> partials(chunk1 - chunk0);
    for (int y = y0; y < y1; ++y) {
        for (auto& p : partials) {
            for (int c = 0; c < NC; ++c)
                p.acc[c] = V::zero();
            p.weight_sum = V::set1(1.f);  // the centre
            p.member_count = V::set1(1.f);
            p.inverse_sum = V::zero();
        }
        if constexpr (kDiagnostics)
            for (int k = chunk0; k < chunk1; ++k)
                partials[k - chunk0].inverse_sum =
                    V::load(L.inverse_count + std::ptrdiff_t(y) * L.stride + k * V::kWidth);
        // Bands in a fixed order: each pixel sums its taps in the same order whatever the
        // tiling, so results stay bitwise identical for any thread count.
        for (int dy0 = -L.pad_y; dy0 <= L.pad_y; dy0 += kBandRows) {
            const int dy1 = std::min(dy0 + kBandRows - 1, L.pad_y);
            for (int k = chunk0; k < chunk1; ++k) {
                if (L.needs_guard(y, k))
                    add_band<V, NC, NG, kDiagnostics, true>(L, y, k * V::kWidth, dy0, dy1, partials[k - chunk0]);
                else
                    add_band<V, NC, NG, kDiagnostics, false>(L, y, k * V::kWidth, dy0, dy1, partials[k - chunk0]);
            }
        }
        for (int k = chunk0; k < chunk1; ++k)
            write_chunk<V, NC, kDiagnostics>(L, out, diag, y, k * V::kWidth, partials[k - chunk0]);
    }
}

template <class V, int NC, int NG>
void filter_rows_diag(const FilterLayout& L, const std::vector<Plane>& out,
                      const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    if (diag.any())
        filter_rows_impl<V, NC, NG, true>(L, out, diag, y0, y1, chunk0, chunk1);
    else
        filter_rows_impl<V, NC, NG, false>(L, out, diag, y0, y1, chunk0, chunk1);
}

template <class V, int NC>
void filter_rows_guides(const FilterLayout& L, const std::vector<Plane>& out,
                        const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    switch (L.guide_count) {
    case 0: return filter_rows_diag<V, NC, 0>(L, out, diag, y0, y1, chunk0, chunk1);
    case 3: return filter_rows_diag<V, NC, 3>(L, out, diag, y0, y1, chunk0, chunk1);
    default: return filter_rows_diag<V, NC, 6>(L, out, diag, y0, y1, chunk0, chunk1);
    }
}

/// Entry point: dispatches on the channel count and guide count at run time, once per call.
template <class V>
void filter_rows(const FilterLayout& L, const std::vector<Plane>& out,
                 const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    switch (L.channels) {
    case 1: return filter_rows_guides<V, 1>(L, out, diag, y0, y1, chunk0, chunk1);
    case 2: return filter_rows_guides<V, 2>(L, out, diag, y0, y1, chunk0, chunk1);
    case 3: return filter_rows_guides<V, 3>(L, out, diag, y0, y1, chunk0, chunk1);
    default: return filter_rows_guides<V, 4>(L, out, diag, y0, y1, chunk0, chunk1);
    }
}

}  // namespace
}  // namespace statmc::detail
