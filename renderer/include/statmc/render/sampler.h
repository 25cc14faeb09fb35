// The random numbers of one camera sample. Each (seed, pixel, sample index) triple gets its
// own PCG32 stream, so a pixel's samples do not depend on which thread renders it, in what
// order tiles run, or how many iterations came before: images are bitwise identical for
// any thread count.
#pragma once

#include <cstdint>

namespace statmc::render {

/// SplitMix64's finaliser: a bijective 64-bit mix, used to turn indices into seeds.
inline std::uint64_t mix64(std::uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/// PCG32 (O'Neill 2014, XSH-RR output) over a 64-bit LCG.
class Sampler {
public:
    Sampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
    {
        const std::uint64_t init = mix64(seed * 0x9e3779b97f4a7c15ULL + mix64(pixel));
        inc_ = (mix64(sample + 0x632be59bd9b4e019ULL * (pixel + 1)) << 1u) | 1u;
        state_ = 0;
        next();
        state_ += init;
        next();
    }

    std::uint32_t next()
    {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        const auto xorshifted = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        const auto rot = std::uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

    /// A uniform float in [0, 1): 24 random bits, so 1 is never returned.
    float get1d() { return float(next() >> 8) * 0x1p-24f; }

private:
    std::uint64_t state_ = 0;
    std::uint64_t inc_ = 1;
};

}  // namespace statmc::render
