// The AVX-512F build of the filter kernel; this file alone is compiled with -mavx512f.

// GCC 12's AVX-512 intrinsics seed results with _mm512_undefined_ps(), which its own
// -W(maybe-)uninitialized then reports (GCC bug 105593); the warning is false here.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"

#include "filter_kernel.h"
#include "simd_avx512.h"

namespace statmc::detail {
FilterKernel filter_kernel_avx512() { return kernel_build<simd::Avx512>(); }
}  // namespace statmc::detail
