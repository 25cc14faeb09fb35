// One-lane "vector" with the interface of simd_avx2.h and simd_avx512.h, so the filter kernel
// compiles as a portable fallback from the same source.
#pragma once

#include <cmath>

namespace statmc::simd {

struct Scalar {
    using F = float;
    using M = bool;
    static constexpr int kWidth = 1;

    static F load(const float* p) { return *p; }
    static F set1(float x) { return x; }
    static F zero() { return 0.f; }
    static F add(F a, F b) { return a + b; }
    static F sub(F a, F b) { return a - b; }
    static F min(F a, F b) { return a < b ? a : b; }  // as minps, ties to b
    static F mul(F a, F b) { return a * b; }
    static F div(F a, F b) { return a / b; }
    // Unfused on purpose: without hardware FMA, std::fma is a slow library call.
    static F fmadd(F a, F b, F c) { return a * b + c; }
    static F fmsub(F a, F b, F c) { return a * b - c; }
    static F fnmadd(F a, F b, F c) { return c - a * b; }
    static M le(F a, F b) { return a <= b; }
    static M le_and(M m, F a, F b) { return m && a <= b; }
    static F select(M m, F a) { return m ? a : 0.f; }
    static F masked_fmadd(M m, F a, F b, F c) { return fmadd(select(m, a), b, c); }
    static F masked_add(M m, F acc, F a) { return add(acc, select(m, a)); }
    static M eq(F a, F b) { return a == b; }
    static bool none(M m) { return !m; }
    static bool all(M m) { return m; }
    static F round(F x) { return std::nearbyint(x); }
    static F scale_by_power_of_two(F p, F n) { return n < -125.f ? 0.f : std::ldexp(p, int(n)); }
    static void store(float* p, F v) { *p = v; }
    static void in_register(F&) {}
};

}  // namespace statmc::simd
