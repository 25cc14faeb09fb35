// The portable build of the filter kernel.
#include "filter_kernel.h"
#include "simd_scalar.h"

namespace statmc::detail {
FilterRowsFn filter_rows_scalar() { return &filter_rows<simd::Scalar>; }
}  // namespace statmc::detail
