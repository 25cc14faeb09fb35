// Online central moments: single-sample updates and exact pairwise merges.
#pragma once

namespace statmc {

/// Running mean and central sums Mk = Σ(x − mean)^k, k = 2..4, of one quantity. The count
/// is kept by the caller so that the channels of one pixel share it. M3 of the Box-Cox
/// values feeds Johnson's correction; M3 and M4 merge exactly (format version 2).
template <class Real>
struct CentralMoments {
    Real mean = 0;
    Real m2 = 0;
    Real m3 = 0;
    Real m4 = 0;

    /// Adds x as value number n + 1, n being the count before the call
    /// (Welford for M2; Pébay 2008, Eq. 2.3, for M3 and M4). Each sum uses the lower ones
    /// before they are updated.
    void add(Real n, Real x)
    {
        const Real n1 = n + 1;
        const Real delta = x - mean;
        const Real delta_n = delta / n1;
        const Real delta_n2 = delta_n * delta_n;
        const Real term = delta * delta_n * n;
        mean += delta_n;
        m4 += term * delta_n2 * (n1 * n1 - 3 * n1 + 3) + 6 * delta_n2 * m2 - 4 * delta_n * m3;
        m3 += term * delta_n * (n1 - 2) - 3 * delta_n * m2;
        m2 += term;
    }

    /// Folds in `other`, the moments of `nb` further values, `na` being this set's count
    /// (Chan et al. 1979; Pébay 2008, Eq. 2.1). Exact up to rounding: merge(A, B) == A ∪ B.
    void merge(Real na, const CentralMoments& other, Real nb)
    {
        const Real n = na + nb;
        if (nb == 0)
            return;
        if (na == 0) {
            *this = other;
            return;
        }
        const Real delta = other.mean - mean;
        const Real delta_n = delta / n;
        const Real delta_n2 = delta_n * delta_n;
        m4 += other.m4 + delta * delta_n * delta_n2 * na * nb * (na * na - na * nb + nb * nb) +
              6 * delta_n2 * (na * na * other.m2 + nb * nb * m2) +
              4 * delta_n * (na * other.m3 - nb * m3);
        m3 += other.m3 + delta * delta_n2 * na * nb * (na - nb) +
              3 * delta_n * (na * other.m2 - nb * m2);
        m2 += other.m2 + delta * delta_n * na * nb;
        mean += delta_n * nb;
    }
};

}  // namespace statmc
