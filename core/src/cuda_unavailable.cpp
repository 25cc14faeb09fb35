// The CUDA entry points of a build without the CUDA path (STATMC_CUDA=OFF, or no nvcc
// found): every answer says so, and device=cuda is an error that names the reason.
#include <stdexcept>

#include "filter_cuda.h"
#include "statmc/core/cuda_device.h"

namespace statmc {

namespace {
constexpr const char* kWhy =
    "this statmc was built without CUDA (configure with -DSTATMC_CUDA=ON where nvcc is "
    "installed)";
}

bool built_with_cuda() { return false; }

bool cuda_available(std::string* why)
{
    if (why)
        *why = kWhy;
    return false;
}

std::string cuda_device_description() { return {}; }

namespace detail {

struct CudaFilter::Impl {};

CudaFilter::CudaFilter(const FilterLayout&, bool) { throw std::runtime_error(kWhy); }
CudaFilter::~CudaFilter() = default;
void CudaFilter::run(const FilterLayout&, const std::vector<Plane>&, const FilterDiagnostics&) {}
CudaTimings CudaFilter::timings() const { return {}; }

}  // namespace detail
}  // namespace statmc
