// 2^x for x ≤ 0, written once over a SIMD type V (simd_scalar.h, simd_avx2.h,
// simd_avx512.h): the guide weights' only transcendental.
#pragma once

namespace statmc::simd {

/// 2^x to ~2 ulp for x ≤ 0 (any magnitude: 0 below the float range). The fraction
/// f = x − round(x) ∈ [−½, ½] is exact; 2^f is Cephes exp2f's polynomial, evaluated by
/// Estrin's scheme, whose shallower dependency chain matters more here than its one extra
/// multiply: each tap's weight waits on it. V::scale_by_power_of_two applies 2^round(x).
template <class V>
inline typename V::F exp2_nonpositive(typename V::F x)
{
    using F = typename V::F;
    const F n = V::round(x);
    const F f = V::sub(x, n);
    const F f2 = V::mul(f, f);
    const F a = V::fmadd(V::set1(2.402264791363012e-1f), f, V::set1(6.931472028550421e-1f));
    const F b = V::fmadd(V::set1(9.618437357674640e-3f), f, V::set1(5.550332471162809e-2f));
    const F c = V::fmadd(V::set1(1.535336188319500e-4f), f, V::set1(1.339887440266574e-3f));
    const F q = V::fmadd(c, V::mul(f2, f2), V::fmadd(b, f2, a));
    return V::scale_by_power_of_two(V::fmadd(q, f, V::set1(1.f)), n);
}

}  // namespace statmc::simd
