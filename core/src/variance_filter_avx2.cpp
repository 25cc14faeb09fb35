// The AVX2 build of the variance filter's disk loop: four pixels per vector, in double.
// Built with -mavx2 -ffp-contract=off (core/CMakeLists.txt), so that it rounds as the
// scalar loop does.
#include "variance_filter_kernel.h"

namespace statmc::detail {
VarianceKernel variance_kernel_avx2() { return {4, &add_variance_disk<4>}; }
}  // namespace statmc::detail
