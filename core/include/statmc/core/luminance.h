// Luminance: the one weighting of R,G,B used wherever a single value stands for a colour
// (the sample rule, the per-bounce statistics, light power, SSIM's grey image).
#pragma once

namespace statmc {

/// Rec. 709 luminance with the CIE Y coefficients of linear sRGB primaries (docs/method.md §2).
template <class Real>
inline Real luminance(Real r, Real g, Real b)
{
    return Real(0.212671) * r + Real(0.715160) * g + Real(0.072169) * b;
}

}  // namespace statmc
