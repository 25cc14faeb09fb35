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
    static bool none(M m) { return _mm256_movemask_ps(m) == 0; }
    static void store(float* p, F v) { _mm256_storeu_ps(p, v); }

    /// e^x to ~2 ulp for x in [−87.3, 88.3] (Cephes expf: range reduction by ln 2,
    /// degree-5 polynomial, exponent by integer add); clamps above that range and gives 0
    /// below it, as std::exp and the AVX-512 kernel do (a clamp would leave weights of
    /// ~1e-38 where they vanish).
    static F exp(F x)
    {
        const M vanishes = _mm256_cmp_ps(x, set1(-87.3365447505531f), _CMP_LT_OQ);
        x = _mm256_min_ps(x, set1(88.3762626647949f));
        x = _mm256_max_ps(x, set1(-87.3365447505531f));
        const F fx = _mm256_floor_ps(fmadd(x, set1(1.44269504088896341f), set1(0.5f)));
        x = fnmadd(fx, set1(0.693359375f), x);
        x = fnmadd(fx, set1(-2.12194440e-4f), x);
        F y = set1(1.9875691500e-4f);
        y = fmadd(y, x, set1(1.3981999507e-3f));
        y = fmadd(y, x, set1(8.3334519073e-3f));
        y = fmadd(y, x, set1(4.1665795894e-2f));
        y = fmadd(y, x, set1(1.6666665459e-1f));
        y = fmadd(y, x, set1(5.0000001201e-1f));
        y = fmadd(y, mul(x, x), add(x, set1(1.f)));
        const __m256i e = _mm256_slli_epi32(
            _mm256_add_epi32(_mm256_cvtps_epi32(fx), _mm256_set1_epi32(127)), 23);
        return _mm256_andnot_ps(vanishes, mul(y, _mm256_castsi256_ps(e)));
    }
};

}  // namespace statmc::simd
