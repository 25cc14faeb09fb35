// The portable build of the filter kernel.
#include "filter_kernel.h"
#include "simd_scalar.h"

namespace statmc::detail {
FilterKernel filter_kernel_scalar() { return kernel_build<simd::Scalar>(); }
}  // namespace statmc::detail
