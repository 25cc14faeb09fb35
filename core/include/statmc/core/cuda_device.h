// Whether the filter can run on a CUDA GPU here (docs/gpu.md): the build must have the CUDA
// path (CMake STATMC_CUDA) and the machine a device with a working driver.
#pragma once

#include <cstddef>
#include <string>

namespace statmc {

/// Whether this build carries the CUDA path at all.
bool built_with_cuda();

/// Whether a CUDA device can run the filter. When not, `why` (if given) says why in words:
/// built without CUDA, no driver, or no device.
bool cuda_available(std::string* why = nullptr);

/// The device the filter would use, in words ("NVIDIA H200, compute capability 9.0, 132
/// multiprocessors"), or empty when cuda_available() is false.
std::string cuda_device_description();

/// With Device::Auto, images of at least this many pixels go to the GPU: below it the
/// transfers and the launch cost more than the CPU's filter (docs/gpu.md).
constexpr std::size_t kAutoCudaPixels = std::size_t(512) * 512;

}  // namespace statmc
