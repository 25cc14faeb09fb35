// The Box-Cox transform used by the membership test, and the sample sanitising rule.
#pragma once

#include <cmath>

#include "statmc/core/luminance.h"

namespace statmc {

/// Box-Cox exponent, fixed as in the method (docs/method.md §2).
inline constexpr double kBoxCoxLambda = 0.5;

/// y = (x^λ − 1)/λ with λ = 1/2, i.e. 2√x − 2; negative inputs are clamped to 0 first.
template <class Real>
inline Real box_cox(Real x)
{
    return Real(2) * std::sqrt(x > Real(0) ? x : Real(0)) - Real(2);
}

/// Whether a sample is counted as measured or as 0: NaN, infinite, or clearly negative
/// luminance marks a broken sample (docs/method.md §2, a choice of the authors' code).
/// For one channel the value stands for the luminance.
inline bool sample_is_usable(const float* sample, int channels)
{
    for (int c = 0; c < channels; ++c)
        if (!std::isfinite(sample[c]))
            return false;
    const double y =
        channels >= 3 ? luminance<double>(sample[0], sample[1], sample[2]) : double(sample[0]);
    return y >= -1e-5;
}

}  // namespace statmc
