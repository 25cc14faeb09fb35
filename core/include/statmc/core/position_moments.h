// Co-moments of a pixel's samples with where in the pixel they were taken: what the
// explained-variance correction (explained_variance.h, docs/method.md §12) needs.
#pragma once

namespace statmc {

/// For one pixel, the sub-pixel offsets (u, v) ∈ [0, 1)² of its samples (mean and central
/// sums Σ(u − ū)², Σ(v − v̄)², Σ(u − ū)(v − v̄)), and per channel the co-moments
/// Σ(f − f̄)(u − ū), Σ(f − f̄)(v − v̄) of the untransformed and the Box-Cox values f. The
/// count and the value means belong to the pixel's PixelMoments, which passes them in.
template <int C, class Real = double>
struct PositionMoments {
    Real mean_u = 0, mean_v = 0;
    Real m2_uu = 0, m2_vv = 0, m2_uv = 0;
    Real raw_u[C] = {}, raw_v[C] = {};
    Real bc_u[C] = {}, bc_v[C] = {};

    /// Adds the sample number n + 1 at (u, v) with values raw[c], bc[c]; raw_mean and
    /// bc_mean are the pixel's value means before it (Welford's co-moment update:
    /// C += n/(n + 1)·δu·δf, δ taken against the old means).
    void add(Real n, Real u, Real v, const Real* raw, const Real* raw_mean, const Real* bc,
             const Real* bc_mean)
    {
        const Real w = n / (n + 1);
        const Real du = u - mean_u, dv = v - mean_v;
        for (int c = 0; c < C; ++c) {
            const Real dr = raw[c] - raw_mean[c], db = bc[c] - bc_mean[c];
            raw_u[c] += w * du * dr;
            raw_v[c] += w * dv * dr;
            bc_u[c] += w * du * db;
            bc_v[c] += w * dv * db;
        }
        m2_uu += w * du * du;
        m2_vv += w * dv * dv;
        m2_uv += w * du * dv;
        mean_u += du / (n + 1);
        mean_v += dv / (n + 1);
    }

    /// Folds in `other`, the co-moments of `nb` further samples, `na` being this set's
    /// count; delta_raw[c], delta_bc[c] are the other set's value means minus this set's
    /// (C = C_A + C_B + δu·δf·n_A·n_B/n, Pébay 2008). Exact up to rounding.
    void merge(Real na, const PositionMoments& other, Real nb, const Real* delta_raw,
               const Real* delta_bc)
    {
        if (nb == 0)
            return;
        if (na == 0) {
            *this = other;
            return;
        }
        const Real n = na + nb, w = na * nb / n;
        const Real du = other.mean_u - mean_u, dv = other.mean_v - mean_v;
        for (int c = 0; c < C; ++c) {
            raw_u[c] += other.raw_u[c] + w * du * delta_raw[c];
            raw_v[c] += other.raw_v[c] + w * dv * delta_raw[c];
            bc_u[c] += other.bc_u[c] + w * du * delta_bc[c];
            bc_v[c] += other.bc_v[c] + w * dv * delta_bc[c];
        }
        m2_uu += other.m2_uu + w * du * du;
        m2_vv += other.m2_vv + w * dv * dv;
        m2_uv += other.m2_uv + w * du * dv;
        mean_u += du * nb / n;
        mean_v += dv * nb / n;
    }
};

}  // namespace statmc
