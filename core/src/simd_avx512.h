// Sixteen float lanes on AVX-512F. Include only from translation units compiled with
// -mavx512f; the filter chooses them at run time.
//
// Masks live in k registers, so the kernel's "all channels pass" chain is a masked
// compare and its masked accumulation a single masked FMA: fewer operations per lane
// than AVX2's compare-and-blend, on twice the lanes. Without guides every operation rounds
// exactly as its AVX2 counterpart, so both kernels give the same bits; the guide weight's
// power of two is applied by vscalefps, which gives the same bits as AVX2's exponent
// arithmetic.
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
    static F min(F a, F b) { return _mm512_min_ps(a, b); }
    static F mul(F a, F b) { return _mm512_mul_ps(a, b); }
    static F div(F a, F b) { return _mm512_div_ps(a, b); }
    static F fmadd(F a, F b, F c) { return _mm512_fmadd_ps(a, b, c); }
    static F fmsub(F a, F b, F c) { return _mm512_fmsub_ps(a, b, c); }
    static F fnmadd(F a, F b, F c) { return _mm512_fnmadd_ps(a, b, c); }
    // Ordered compare: a NaN operand gives false, so NaN never makes a member.
    static M le(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ); }
    static M le_and(M m, F a, F b) { return _mm512_mask_cmp_ps_mask(m, a, b, _CMP_LE_OQ); }
    static F masked_fmadd(M m, F a, F b, F c) { return _mm512_mask3_fmadd_ps(a, b, c, m); }
    static F masked_add(M m, F acc, F a) { return _mm512_mask_add_ps(acc, m, acc, a); }
    static M eq(F a, F b) { return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ); }
    static bool none(M m) { return m == 0; }
    static bool all(M m) { return m == 0xffff; }
    static void store(float* p, F v) { _mm512_storeu_ps(p, v); }
    /// Makes a loaded value live in a register: GCC would otherwise fold the load into
    /// each of its users as a memory operand, loading it once per user.
    static void in_register(F& v) { asm("" : "+v"(v)); }

    static F round(F x)
    {
        return _mm512_roundscale_ps(x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    }
    /// p·2^n by vscalefps for p ∈ [½, 2]; 0 where 2^n would be denormal or less, as in
    /// AVX2 (denormal weights would slow the FMAs that add them, and round differently).
    static F scale_by_power_of_two(F p, F n)
    {
        return _mm512_maskz_scalef_ps(_mm512_cmp_ps_mask(n, set1(-125.f), _CMP_GE_OQ), p, n);
    }
};

}  // namespace statmc::simd
