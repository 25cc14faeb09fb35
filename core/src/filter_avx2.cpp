// The AVX2 + FMA build of the filter kernel; this file alone is compiled with -mavx2 -mfma.
#include "filter_kernel.h"
#include "simd_avx2.h"

namespace statmc::detail {
FilterKernel filter_kernel_avx2() { return kernel_build<simd::Avx2>(); }
}  // namespace statmc::detail
