// The parameters of the StatMC filter (docs/method.md §5), with the paper's defaults.
#pragma once

#include <string>

namespace statmc {

/// Where the filter kernel runs (docs/gpu.md).
enum class Device {
    Cpu,   ///< the reference: the same bits on every machine
    Cuda,  ///< a CUDA GPU (core/cuda/); an error where there is none or the build has no CUDA
    Auto,  ///< a CUDA GPU when one is present and the image is large enough to pay for it
};

struct DenoiseOptions {
    int radius = 20;             ///< disk radius in pixels, ≥ 0
    double alpha = 0.005;        ///< significance level of the t-test, in (0, 1)
    float sigma_spatial = 10.f;  ///< Gaussian spatial falloff in pixels, > 0
    float sigma_albedo = 0.02f;  ///< albedo guide falloff, > 0 (used only with an albedo guide)
    float sigma_normal = 0.1f;   ///< normal guide falloff, > 0 (used only with a normal guide)
    /// Firefly guard (firefly_guard.h): a centre accepts no neighbour whose noise level
    /// (the Box-Cox sample variance, or s²/μ for the untransformed test) exceeds this many
    /// times its own reference level. 0 = off, the paper's filter; else ≥ 1.
    float firefly_ratio = 256.f;
    /// Guide noise (docs/method.md §5): with the guides' variances (Guides), take the part
    /// of a guide distance that their sampling noise explains out of the guide weight, the
    /// less noisy pixel's twice, so that i weighs j as j weighs i.
    /// Off in the paper's filter; without the variances it changes nothing.
    bool guide_noise = true;
    /// The GPU gives the same members and values within float summation order (docs/gpu.md);
    /// only the CPU gives the paper's bits.
    Device device = Device::Cpu;

    /// Empty when valid, else a message naming the offending parameter.
    std::string validate() const;

    /// The filter as the paper describes it: these defaults with the firefly guard and the
    /// guide-noise correction off.
    static DenoiseOptions paper();
};

}  // namespace statmc
