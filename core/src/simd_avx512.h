// Sixteen float lanes on AVX-512F. Include only from translation units compiled with
// -mavx512f; the filter chooses them at run time.
//
// Masks live in k registers, so the kernel's "all channels pass" chain is a masked
// compare and its masked accumulation a single masked FMA: fewer operations per lane
// than AVX2's compare-and-blend, on twice the lanes. Without guides every operation rounds
// exactly as its AVX2 counterpart, so both kernels give the same bits; the guide weight's
// exp applies its power of two with vscalefps and may differ from AVX2's in the last bit.
#pragma once

#include <immintrin.h>

namespace statmc::simd {

struct Avx512 {
    using F = __m512;
    using M = __mmask16;
    static constexpr int kWidth = 16;

    static F load(const float* p) { return _mm512_loadu_ps(p); }
    static F set1(float x) { return _mm512_set1_ps(x); }
    static F zero() { return _mm512_setzero_ps(); }
    static F add(F a, F b) { return _mm512_add_ps(a, b); }
    static F sub(F a, F b) { return _mm512_sub_ps(a, b); }
    static F mul(F a, F b) { return _mm512_mul_ps(a, b); }
    static F div(F a, F b) { return _mm512_div_ps(a, b); }
    static F fmadd(F a, F b, F c) { return _mm512_fmadd_ps(a, b, c); }
    static F fmsub(F a, F b, F c) { return _mm512_fmsub_ps(a, b, c); }
    static F fnmadd(F a, F b, F c) { return _mm512_fnmadd_ps(a, b, c); }
    // Ordered compare: a NaN operand gives false, so NaN never makes a member.
    static M le(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
    static M le_and(M m, F a, F b) { return _mm512_mask_cmp_ps_mask(m, a, b, _CMP_LE_OQ); }
    static F select(M m, F a) { return _mm512_maskz_mov_ps(m, a); }
    static F masked_fmadd(M m, F a, F b, F c) { return _mm512_mask3_fmadd_ps(a, b, c, m); }
    static F masked_add(M m, F acc, F a) { return _mm512_mask_add_ps(acc, m, acc, a); }
    static bool none(M m) { return m == 0; }
    static void store(float* p, F v) { _mm512_storeu_ps(p, v); }

    /// e^x for x ≤ 0 to ~2 ulp: Cephes expf's reduction and polynomial, with the power of
    /// two applied by vscalefps, which also flushes x → −∞ to 0 without clamping.
    static F exp(F x)
    {
        const F n = _mm512_roundscale_ps(mul(x, set1(1.44269504088896341f)),
                                         _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
        x = fnmadd(n, set1(0.693359375f), x);
        x = fnmadd(n, set1(-2.12194440e-4f), x);
        F y = set1(1.9875691500e-4f);
        y = fmadd(y, x, set1(1.3981999507e-3f));
        y = fmadd(y, x, set1(8.3334519073e-3f));
        y = fmadd(y, x, set1(4.1665795894e-2f));
        y = fmadd(y, x, set1(1.6666665459e-1f));
        y = fmadd(y, x, set1(5.0000001201e-1f));
        y = fmadd(y, mul(x, x), add(x, set1(1.f)));
        return _mm512_scalef_ps(y, n);
    }
};

}  // namespace statmc::simd
