// The AVX-512F build of the variance filter's disk loop: eight pixels per vector, in
// double. Built with -mavx512f -ffp-contract=off (core/CMakeLists.txt): a fused
// multiply-add would round differently from the scalar loop.
#include "variance_filter_kernel.h"

namespace statmc::detail {
VarianceKernel variance_kernel_avx512() { return {8, &add_variance_disk<8>}; }
}  // namespace statmc::detail
