// Bitwise equality of floats, for tests that promise the same bits: NaN equals a NaN of the
// same payload, and 0 differs from -0. Header-only, so that core-only tests can use it.
#pragma once

#include <cstring>
#include <vector>

namespace statmc::test {

inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

inline bool same_bits(const std::vector<float>& a, const std::vector<float>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace statmc::test
