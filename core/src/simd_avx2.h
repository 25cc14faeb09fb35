// Eight float lanes on AVX2 + FMA. Include only from translation units compiled with
// -mavx2 -mfma; the filter chooses them at run time.
#pragma once

#include <immintrin.h>

namespace statmc::simd {

struct Avx2 {
    using F = __m256;
    using M = __m256;  // all-ones lanes where true, as _mm256_cmp_ps produces
    static constexpr int kWidth = 8;

    static F load(const float* p) { return _mm256_loadu_ps(p); }
    static F set1(float x) { return _mm256_set1_ps(x); }
    static F zero() { return _mm256_setzero_ps(); }
    static F add(F a, F b) { return _mm256_add_ps(a, b); }
    static F sub(F a, F b) { return _mm256_sub_ps(a, b); }
    static F min(F a, F b) { return _mm256_min_ps(a, b); }
    static F mul(F a, F b) { return _mm256_mul_ps(a, b); }
    static F div(F a, F b) { return _mm256_div_ps(a, b); }
    static F fmadd(F a, F b, F c) { return _mm256_fmadd_ps(a, b, c); }
    static F fmsub(F a, F b, F c) { return _mm256_fmsub_ps(a, b, c); }
    static F fnmadd(F a, F b, F c) { return _mm256_fnmadd_ps(a, b, c); }
    // Ordered compare: a NaN operand gives false, so NaN never makes a member.
    static M le(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
    static M le_and(M m, F a, F b) { return _mm256_and_ps(m, le(a, b)); }
    static F select(M m, F a) { return _mm256_and_ps(m, a); }
    // Masked lanes add 0·b, which leaves c as it is for the finite b the kernel passes.
    static F masked_fmadd(M m, F a, F b, F c) { return fmadd(select(m, a), b, c); }
    static F masked_add(M m, F acc, F a) { return add(acc, select(m, a)); }
    static M eq(F a, F b) { return _mm256_cmp_ps(a, b, _CMP_EQ_OQ); }
    static bool none(M m) { return _mm256_movemask_ps(m) == 0; }
    static bool all(M m) { return _mm256_movemask_ps(m) == 0xff; }
    static void store(float* p, F v) { _mm256_storeu_ps(p, v); }
    static void in_register(F& v) { asm("" : "+x"(v)); }

    static F round(F x)
    {
        return _mm256_round_ps(x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
    }
    /// p·2^n for p ∈ [½, 2] by exponent arithmetic; 0 where 2^n would be denormal or
    /// less (a clamp would leave weights of ~1e-38, whose denormal FMAs are slow).
    static F scale_by_power_of_two(F p, F n)
    {
        const M vanishes = _mm256_cmp_ps(n, set1(-125.f), _CMP_LT_OQ);
        const __m256i e =
            _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvtps_epi32(n), _mm256_set1_epi32(127)), 23);
        return _mm256_andnot_ps(vanishes, mul(p, _mm256_castsi256_ps(e)));
    }
};

}  // namespace statmc::simd
