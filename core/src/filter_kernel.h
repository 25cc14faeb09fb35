// The filter's inner loop, written once over a SIMD type V (simd_scalar.h, simd_avx2.h,
// simd_avx512.h). Lanes are consecutive output pixels of one row, so a tap is a few
// unaligned loads and streaming arithmetic; where the registers allow, two rows walk
// their windows together (centre_rows()).
//
// Everything here has internal linkage on purpose: the header is compiled once per
// instruction set, and shared inline symbols could let the linker mix the two builds.
#pragma once

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>
#include <type_traits>

#include "filter_layout.h"
#include "simd_exp2.h"

// The tap code must be inlined into its loops: GCC's size heuristics otherwise outline
// it once it has a few call sites, and every call then pays a vzeroupper and spills.
#define STATMC_INLINE __attribute__((always_inline))

namespace statmc::detail {
namespace {

/// What a chunk of lanes has gathered so far; carried from one band of rows to the next.
/// NA: the channels averaged (the leading ones; the rest are only tested, FilterLayout).
template <class V, int NA>
struct Partial {
    typename V::F acc[NA];  // Σ W_ij (F_j − F_i)
    typename V::F weight_sum;
    typename V::F member_count;
    typename V::F inverse_sum;  // Σ W_ij² / n_j, for the effective sample count
};

/// One centre chunk's registers during a band: what it tests and averages against, and
/// what it has gathered.
template <class V, int NC, int NA, int NG>
struct CentreState {
    using F = typename V::F;
    F mean[NC], threshold[NC], noise_limit, noise_level;
    F value[NA];
    F guide[NG > 0 ? NG : 1];
    F guide_noise;
    Partial<V, NA> gathered;
};

template <int K>
using Row = std::integral_constant<int, K>;

/// Which of two paired centre rows take a run of columns.
enum Takers : int { kFirst = 1, kSecond = 2, kBoth = 3 };

/// Up to three runs of columns, ascending, each taken by the same centres.
struct ColumnPieces {
    struct Piece {
        int from, to, who;
    } piece[3];
    int count = 0;
};

/// Splits the columns [lo0, hi0] (the first centre's; empty when lo0 > hi0) and [lo1, hi1]
/// (the second's) into runs taken by one centre or by both.
inline void split_columns(int lo0, int hi0, int lo1, int hi1, ColumnPieces& out)
{
    auto add = [&](int from, int to, int who) { out.piece[out.count++] = {from, to, who}; };
    const bool none0 = lo0 > hi0, none1 = lo1 > hi1;
    if (none0 || none1) {
        if (!none0)
            add(lo0, hi0, kFirst);
        if (!none1)
            add(lo1, hi1, kSecond);
        return;
    }
    const int from = std::max(lo0, lo1), to = std::min(hi0, hi1);
    if (from > to) {  // apart: each alone, the nearer first
        if (lo0 < lo1) {
            add(lo0, hi0, kFirst);
            add(lo1, hi1, kSecond);
        } else {
            add(lo1, hi1, kSecond);
            add(lo0, hi0, kFirst);
        }
        return;
    }
    if (lo0 != lo1)
        add(std::min(lo0, lo1), from - 1, lo0 < lo1 ? kFirst : kSecond);
    add(from, to, kBoth);
    if (hi0 != hi1)
        add(to + 1, std::max(hi0, hi1), hi0 > hi1 ? kFirst : kSecond);
}

/// Adds the taps of absolute window rows [y_first, y_last] to the R chunks of lanes that
/// start at (x0, y), (x0, y + 1), …: R = 2 centre rows share every neighbour load, which
/// halves the loads per tap, and with guides lets two rows' weight chains overlap. NC
/// channels are tested, the first NA of them averaged.
template <class V, int NC, int NA, int NG, bool kNoise, int R, bool kDiagnostics, bool kGuard>
void add_band(const FilterLayout& L, int y, int x0, int y_first, int y_last,
              Partial<V, NA>* partial)
{
    using F = typename V::F;
    CentreState<V, NC, NA, NG> ctr[R];
    for (int k = 0; k < R; ++k) {
        // Σ W_ij (F_j − F_i) rather than Σ W_ij F_j: out_i = F_i + that / Σ W_ij is the
        // same average, but members equal to the centre add exactly nothing, so flat
        // regions come back bit for bit and large offsets (HDR) lose no digits.
        const std::ptrdiff_t centre = std::ptrdiff_t(y + k) * L.stride + x0;
        CentreState<V, NC, NA, NG>& s = ctr[k];
        for (int c = 0; c < NC; ++c) {
            s.mean[c] = V::load(L.mean[c] + centre);
            s.threshold[c] = V::load(L.threshold[c] + centre);
        }
        for (int c = 0; c < NA; ++c)
            s.value[c] = V::load(L.value[c] + centre);
        if constexpr (kGuard) {
            s.noise_limit = V::load(L.noise_limit + centre);
            s.noise_level = V::load(L.noise_own + centre);
        }
        for (int g = 0; g < NG; ++g)
            s.guide[g] = V::load(L.guide[g] + centre);
        if constexpr (kNoise)
            s.guide_noise = V::load(L.guide_noise + centre);
        s.gathered = partial[k];
    }

    // The taps at column offset dx of window row wy for the centre rows y + k,
    // k ∈ [First, Last): channel by channel, so each neighbour value is loaded once for all.
    auto taps = [&](auto first, auto last, int dx, int wy) STATMC_INLINE {
        constexpr int First = decltype(first)::value, Last = decltype(last)::value;
        const std::ptrdiff_t off = std::ptrdiff_t(wy) * L.stride + x0 + dx;
        // Membership: all channels pass (μ̃_i − μ̃_j)² − T_j ≤ T_i, the fast form of
        // docs/method.md §4, (μ̃_i − μ̃_j)² ≤ γ_i²v_i + γ_j²v_j, kept in difference form:
        // expanding it into D_i + D_j ≤ 2μ̃_iμ̃_j cancels catastrophically in float once
        // v ≪ μ̃² (high spp). The firefly guard, where needed, starts the mask chain; it is
        // mutual for centres whose value rests on several samples: a glint its neighbour
        // would refuse does not take that neighbour either, and keeps its light
        // (firefly_guard.h).
        typename V::M m[R];
        if constexpr (kGuard) {
            const F level = V::load(L.noise + off), limit = V::load(L.noise_mutual + off);
            for (int k = First; k < Last; ++k)
                m[k] = V::le_and(V::le(level, ctr[k].noise_limit), ctr[k].noise_level, limit);
        }
        for (int c = 0; c < NC; ++c) {
            F mean = V::load(L.mean[c] + off), threshold = V::load(L.threshold[c] + off);
            if constexpr (Last - First > 1) {
                V::in_register(mean);
                V::in_register(threshold);
            }
            for (int k = First; k < Last; ++k) {
                const F d = V::sub(ctr[k].mean[c], mean);
                const F excess = V::fmsub(d, d, threshold);
                m[k] = c == 0 && !kGuard ? V::le(excess, ctr[k].threshold[c])
                                         : V::le_and(m[k], excess, ctr[k].threshold[c]);
            }
        }
        F w[R];
        if constexpr (NG == 0) {
            for (int k = First; k < Last; ++k)
                w[k] = V::set1(L.spatial(dx, wy - y - k));
        } else {
            // The guide weight costs an exp; a tap no lane accepts adds nothing anyway.
            bool any = false;
            for (int k = First; k < Last; ++k)
                any = any || !V::none(m[k]);
            if (!any)
                return;
            // log2 w = spatial − Σ (Δg)² (guides are stored pre-scaled), summed as two
            // chains joined at the end: the weight's latency bounds this loop.
            constexpr int kHalf = (NG + 1) / 2;
            F near[R], far[R], spatial[R];
            for (int k = First; k < Last; ++k) {
                spatial[k] = V::set1(L.spatial_log2(dx, wy - y - k));
                near[k] = spatial[k];
                far[k] = V::zero();
            }
            for (int g = 0; g < NG; ++g) {
                F guide = V::load(L.guide[g] + off);
                if constexpr (Last - First > 1)
                    V::in_register(guide);
                for (int k = First; k < Last; ++k) {
                    const F d = V::sub(ctr[k].guide[g], guide);
                    if (g < kHalf)
                        near[k] = V::fnmadd(d, d, near[k]);
                    else
                        far[k] = g == kHalf ? V::mul(d, d) : V::fmadd(d, d, far[k]);
                }
            }
            // The exponent; where every lane's is exactly the spatial one (guides that agree,
            // as on a flat wall, or guide noise that explains their whole distance), its exp2
            // is in a table. Left as it was written, so that the compiler fuses it as before.
            F log2_weight[R];
            if constexpr (kNoise) {
                // Guide noise: spatial − max(0, Σ(Δg)² − 2·min(u_i, u_j)), the same both ways
                // (docs/method.md §5). With u = 0 it adds +0: the bits of the loop below.
                const F noise = V::load(L.guide_noise + off);
                for (int k = First; k < Last; ++k) {
                    const F shared = V::min(ctr[k].guide_noise, noise);
                    log2_weight[k] = V::min(
                        V::add(V::sub(near[k], far[k]), V::add(shared, shared)), spatial[k]);
                }
            } else {
                for (int k = First; k < Last; ++k)
                    log2_weight[k] = V::sub(near[k], far[k]);
            }
            for (int k = First; k < Last; ++k)
                w[k] = V::all(V::eq(log2_weight[k], spatial[k]))
                           ? V::set1(L.flat_guide(dx, wy - y - k))
                           : simd::exp2_nonpositive<V>(log2_weight[k]);
        }
        for (int c = 0; c < NA; ++c) {
            F value = V::load(L.value[c] + off);
            if constexpr (Last - First > 1)
                V::in_register(value);
            for (int k = First; k < Last; ++k)
                ctr[k].gathered.acc[c] = V::masked_fmadd(m[k], w[k], V::sub(value, ctr[k].value[c]),
                                                         ctr[k].gathered.acc[c]);
        }
        for (int k = First; k < Last; ++k) {
            Partial<V, NA>& g = ctr[k].gathered;
            g.weight_sum = V::masked_add(m[k], g.weight_sum, w[k]);
            if constexpr (kDiagnostics) {
                g.member_count = V::masked_add(m[k], g.member_count, V::set1(1.f));
                g.inverse_sum = V::masked_fmadd(m[k], V::mul(w[k], w[k]),
                                                V::load(L.inverse_count + off), g.inverse_sum);
            }
        }
    };
    auto tap = [&](auto row, int dx, int wy)
                   STATMC_INLINE { taps(row, Row<decltype(row)::value + 1>{}, dx, wy); };
    // Row wy of centre k's window: columns inner < |dx| ≤ outer (−1: none, or from dx = 0).
    auto half_width = [&](int k, int wy) {
        const int dy = wy - (y + k);
        return std::abs(dy) <= L.pad_y ? L.half_width[dy + L.pad_y] : -1;
    };
    auto inner_half_width = [&](int k, int wy) {
        const int dy = wy - (y + k);
        return std::abs(dy) <= L.pad_y ? L.inner_half_width[dy + L.pad_y] : -1;
    };
    // One centre's taps of a row, dx ascending, leaving out the inner disk (at least the
    // centre, which is in already).
    auto row_of_one = [&](auto row, int wy, int hw, int inner) STATMC_INLINE {
        for (int dx = -hw; dx <= std::min(-inner - 1, -1); ++dx)
            tap(row, dx, wy);
        if (inner < 0 && hw >= 0)
            tap(row, 0, wy);
        for (int dx = std::max(inner + 1, 1); dx <= hw; ++dx)
            tap(row, dx, wy);
    };

    for (int wy = y_first; wy <= y_last; ++wy) {
        if constexpr (R == 1) {
            row_of_one(Row<0>{}, wy, half_width(0, wy), inner_half_width(0, wy));
        } else {
            // Both centres take the columns both windows cover, sharing the neighbour's
            // loads; the rest go to one centre alone. Each centre still sums its taps in dx
            // order, as with R = 1: the bits do not depend on how rows were paired.
            const int hw0 = half_width(0, wy), hw1 = half_width(1, wy);
            const int in0 = inner_half_width(0, wy), in1 = inner_half_width(1, wy);
            auto run = [&](int from, int to, int who) STATMC_INLINE {
                if (who == kBoth)
                    for (int dx = from; dx <= to; ++dx)
                        taps(Row<0>{}, Row<2>{}, dx, wy);
                else if (who == kFirst)
                    for (int dx = from; dx <= to; ++dx)
                        tap(Row<0>{}, dx, wy);
                else
                    for (int dx = from; dx <= to; ++dx)
                        tap(Row<1>{}, dx, wy);
            };
            ColumnPieces right;  // dx ≥ 1; dx ≤ −1 is its mirror image
            split_columns(std::max(in0 + 1, 1), hw0, std::max(in1 + 1, 1), hw1, right);
            for (int k = right.count - 1; k >= 0; --k)
                run(-right.piece[k].to, -right.piece[k].from, right.piece[k].who);
            const int centre_column =
                (in0 < 0 && hw0 >= 0 ? kFirst : 0) | (in1 < 0 && hw1 >= 0 ? kSecond : 0);
            if (centre_column)
                run(0, 0, centre_column);
            for (int k = 0; k < right.count; ++k)
                run(right.piece[k].from, right.piece[k].to, right.piece[k].who);
        }
    }
    for (int k = 0; k < R; ++k)
        partial[k] = ctr[k].gathered;
}

template <class V, int NC, bool kDiagnostics>
void write_chunk(const FilterLayout& L, const std::vector<Plane>& out,
                 const FilterDiagnostics& diag, int y, int x0, const Partial<V, NC>& partial)
{
    using F = typename V::F;
    const std::ptrdiff_t centre = std::ptrdiff_t(y) * L.stride + x0;
    F value[NC];
    for (int c = 0; c < NC; ++c)
        value[c] = V::add(V::load(L.value[c] + centre), V::div(partial.acc[c], partial.weight_sum));
    const int n = std::min(V::kWidth, L.width - x0);
    // Where no instantiation splits the channels (filter_rows), a context channel is
    // averaged too, but never written: its caller gives it no plane.
    const int written = std::min(NC, L.averaged);
    // A whole chunk into dense planes (the ladder's rungs, most callers) is stored as
    // vectors; the values are those of the lane-by-lane loop below.
    auto dense = [](const Plane& p) { return !p || p.xstride == 1; };
    bool vectors = n == V::kWidth;
    for (int c = 0; c < written; ++c)
        vectors = vectors && dense(out[c]);
    if constexpr (kDiagnostics)
        vectors = vectors && dense(diag.members) && dense(diag.weight_sum) &&
                  dense(diag.effective_samples);
    if (vectors) {
        for (int c = 0; c < written; ++c)
            V::store(&out[c](x0, y), value[c]);
        if constexpr (kDiagnostics) {
            if (diag.members)
                V::store(&diag.members(x0, y), partial.member_count);
            if (diag.weight_sum)
                V::store(&diag.weight_sum(x0, y), partial.weight_sum);
            if (diag.effective_samples) {
                // inverse > 0 ⇔ inverse ≥ the least positive float; 0 + q is q (q ≥ +0).
                const F w = partial.weight_sum, inverse = partial.inverse_sum;
                const auto positive =
                    V::le(V::set1(std::numeric_limits<float>::denorm_min()), inverse);
                V::store(&diag.effective_samples(x0, y),
                         V::masked_add(positive, V::zero(), V::div(V::mul(w, w), inverse)));
            }
        }
        return;
    }
    float lanes[NC][V::kWidth], wsum[V::kWidth], count[V::kWidth], inverse[V::kWidth];
    for (int c = 0; c < NC; ++c)
        V::store(lanes[c], value[c]);
    if constexpr (kDiagnostics) {
        V::store(wsum, partial.weight_sum);
        V::store(count, partial.member_count);
        V::store(inverse, partial.inverse_sum);
    }
    for (int k = 0; k < n; ++k) {
        for (int c = 0; c < written; ++c)
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

/// Centre rows per pass: two on AVX-512 (32 registers) for up to three averaged channels
/// (and a tested context channel), one elsewhere. With guides or diagnostics the two rows
/// spill a few centre values to the stack, and still win: with guides their two exp chains
/// overlap (guided 350 → 293 ms), the radius ladder's rungs (diagnostics, annuli) went from
/// 488 to 454 ms, and with the context channel 4–6% more (docs/filter-design.md).
template <class V, int NC, int NA>
constexpr int centre_rows()
{
    return V::kWidth == 16 && NC <= 4 && NA <= 3 ? 2 : 1;
}

/// The radius ladder's running sums of one chunk (FilterLayout::carry), in and out.
template <class V, int NC>
void load_carry(const FilterLayout& L, std::ptrdiff_t at, Partial<V, NC>& p)
{
    static_assert(NC <= 4, "the ladder's carry planes hold four channels");
    for (int c = 0; c < NC; ++c)
        p.acc[c] = V::load(L.carry[c] + at);
    p.weight_sum = V::load(L.carry[4] + at);
    p.member_count = V::load(L.carry[5] + at);
    p.inverse_sum = V::load(L.carry[6] + at);
}

template <class V, int NC>
void store_carry(const FilterLayout& L, std::ptrdiff_t at, const Partial<V, NC>& p)
{
    for (int c = 0; c < NC; ++c)
        V::store(L.carry[c] + at, p.acc[c]);
    V::store(L.carry[4] + at, p.weight_sum);
    V::store(L.carry[5] + at, p.member_count);
    V::store(L.carry[6] + at, p.inverse_sum);
}

template <class V, int NC, int NA, int NG, bool kNoise, bool kDiagnostics, int R>
void filter_rows_impl(const FilterLayout& L, const std::vector<Plane>& out,
                      const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    std::vector<std::array<Partial<V, NA>, R>> partials(chunk1 - chunk0);
    // Only the radius ladder carries, and it takes at most four channels.
    constexpr bool kMayCarry = NA <= 4;
    const bool carrying = kMayCarry && L.carry[4] != nullptr;
    for (int y = y0; y < y1; y += R) {
        const int rows = std::min(R, y1 - y);
        // A chunk none of whose rows the call wants is skipped whole: its partial sums,
        // carry and output are left as they are (PixelMask: unspecified there).
        auto skipped = [&](int k) {
            for (int r = 0; r < rows; ++r)
                if (L.computes(y + r, k))
                    return false;
            return true;
        };
        for (int k = chunk0; k < chunk1; ++k) {
            if (skipped(k))
                continue;
            for (int r = 0; r < rows; ++r) {
                Partial<V, NA>& p = partials[k - chunk0][r];
                const std::ptrdiff_t at = std::ptrdiff_t(y + r) * L.stride + k * V::kWidth;
                if constexpr (kMayCarry)
                    if (L.carry_from_previous) {
                        load_carry(L, at, p);
                        continue;
                    }
                for (int c = 0; c < NA; ++c)
                    p.acc[c] = V::zero();
                p.weight_sum = V::set1(1.f);  // the centre
                p.member_count = V::set1(1.f);
                p.inverse_sum = kDiagnostics ? V::load(L.inverse_count + at) : V::zero();
            }
        }
        auto add = [&](auto centre_rows, int k, int wy0, int wy1) {
            constexpr int kRows = decltype(centre_rows)::value;
            Partial<V, NA>* p = partials[k - chunk0].data();
            bool guard = false;
            for (int r = 0; r < kRows; ++r)
                guard = guard || L.needs_guard(y + r, k);
            if (guard)
                add_band<V, NC, NA, NG, kNoise, kRows, kDiagnostics, true>(L, y, k * V::kWidth,
                                                                           wy0, wy1, p);
            else
                add_band<V, NC, NA, NG, kNoise, kRows, kDiagnostics, false>(L, y, k * V::kWidth,
                                                                            wy0, wy1, p);
        };
        // Bands of window rows in a fixed order, and taps in a fixed order within each:
        // every pixel sums its taps in the same order whatever the tiling and pairing of
        // rows, so results stay bitwise identical for any thread count.
        const int last_row = y + rows - 1 + L.reach_y;
        for (int wy0 = y - L.reach_y; wy0 <= last_row; wy0 += kBandRows) {
            const int wy1 = std::min(wy0 + kBandRows - 1, last_row);
            for (int k = chunk0; k < chunk1; ++k) {
                if (skipped(k))
                    continue;
                if (rows == R)
                    add(Row<R>{}, k, wy0, wy1);
                else
                    add(Row<1>{}, k, wy0, wy1);
            }
        }
        for (int k = chunk0; k < chunk1; ++k) {
            if (skipped(k))
                continue;
            for (int r = 0; r < rows; ++r) {
                const Partial<V, NA>& p = partials[k - chunk0][r];
                if constexpr (kMayCarry)
                    if (carrying)
                        store_carry(L, std::ptrdiff_t(y + r) * L.stride + k * V::kWidth, p);
                write_chunk<V, NA, kDiagnostics>(L, out, diag, y + r, k * V::kWidth, p);
            }
        }
    }
}

template <class V, int NC, int NA, int NG, bool kNoise>
void filter_rows_diag(const FilterLayout& L, const std::vector<Plane>& out,
                      const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    constexpr int R = centre_rows<V, NC, NA>();
    if (diag.any())
        filter_rows_impl<V, NC, NA, NG, kNoise, true, R>(L, out, diag, y0, y1, chunk0, chunk1);
    else
        filter_rows_impl<V, NC, NA, NG, kNoise, false, R>(L, out, diag, y0, y1, chunk0, chunk1);
}

/// Guides with their noise (FilterLayout::guide_noise) take their own instantiation, so
/// that guides without it run the loop they always ran.
template <class V, int NC, int NA, int NG>
void filter_rows_noise(const FilterLayout& L, const std::vector<Plane>& out,
                       const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    if (L.guide_noise)
        filter_rows_diag<V, NC, NA, NG, true>(L, out, diag, y0, y1, chunk0, chunk1);
    else
        filter_rows_diag<V, NC, NA, NG, false>(L, out, diag, y0, y1, chunk0, chunk1);
}

template <class V, int NC, int NA = NC>
void filter_rows_guides(const FilterLayout& L, const std::vector<Plane>& out,
                        const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    switch (L.guide_count) {
    case 0:
        return filter_rows_diag<V, NC, NA, 0, false>(L, out, diag, y0, y1, chunk0, chunk1);
    case 3:
        return filter_rows_noise<V, NC, NA, 3>(L, out, diag, y0, y1, chunk0, chunk1);
    default:
        return filter_rows_noise<V, NC, NA, 6>(L, out, diag, y0, y1, chunk0, chunk1);
    }
}

/// Entry point: dispatches on the channel count and guide count at run time, once per call.
/// A layer with its context channel (one tested, not averaged) takes its own instantiation;
/// any other split averages every channel, which leaves the leading ones as they are.
template <class V>
void filter_rows(const FilterLayout& L, const std::vector<Plane>& out,
                 const FilterDiagnostics& diag, int y0, int y1, int chunk0, int chunk1)
{
    if (L.averaged == L.channels - 1) {
        if (L.channels == 2)
            return filter_rows_guides<V, 2, 1>(L, out, diag, y0, y1, chunk0, chunk1);
        if (L.channels == 4)
            return filter_rows_guides<V, 4, 3>(L, out, diag, y0, y1, chunk0, chunk1);
    }
    switch (L.channels) {
    case 1:
        return filter_rows_guides<V, 1>(L, out, diag, y0, y1, chunk0, chunk1);
    case 2:
        return filter_rows_guides<V, 2>(L, out, diag, y0, y1, chunk0, chunk1);
    case 3:
        return filter_rows_guides<V, 3>(L, out, diag, y0, y1, chunk0, chunk1);
    case 4:
        return filter_rows_guides<V, 4>(L, out, diag, y0, y1, chunk0, chunk1);
    case 6:
        return filter_rows_guides<V, 6>(L, out, diag, y0, y1, chunk0, chunk1);
    case 9:
        return filter_rows_guides<V, 9>(L, out, diag, y0, y1, chunk0, chunk1);
    default:
        return filter_rows_guides<V, 12>(L, out, diag, y0, y1, chunk0, chunk1);
    }
}

template <class V>
void exp2_each(const float* x, float* out, std::size_t n)
{
    for (std::size_t i = 0; i < n; ++i) {
        float lanes[V::kWidth];
        V::store(lanes, simd::exp2_nonpositive<V>(V::set1(x[i])));
        out[i] = lanes[0];
    }
}

/// This instruction set's kernel, for the one exported function of its translation unit.
template <class V>
FilterKernel kernel_build()
{
    return {V::kWidth, &filter_rows<V>, &exp2_each<V>};
}

}  // namespace
}  // namespace statmc::detail

#undef STATMC_INLINE
