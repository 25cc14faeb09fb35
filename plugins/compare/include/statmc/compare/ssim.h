// Structural similarity (Wang, Bovik, Sheikh and Simoncelli 2004) of two single-channel
// images with values in [0, 1].
#pragma once

#include <vector>

namespace statmc {

/// Mean SSIM of `a` and `b` (w × h, row-major, values in [0, 1]) with an 11×11 Gaussian
/// window of σ = 1.5, K1 = 0.01, K2 = 0.03 and dynamic range 1. Near the borders the
/// window is truncated to the image and renormalized, so images smaller than the window
/// are compared too.
double mean_ssim(const std::vector<float>& a, const std::vector<float>& b, int w, int h);

}  // namespace statmc
