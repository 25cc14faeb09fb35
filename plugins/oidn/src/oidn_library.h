// The few functions of OIDN's C API (version 2) that statmc calls, declared here and
// resolved from the library at run time, so that OIDN is never needed to build.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

namespace statmc::oidn_api {

using Device = struct DeviceImpl*;
using Filter = struct FilterImpl*;

inline constexpr int kDeviceTypeCpu = 1;  // OIDN_DEVICE_TYPE_CPU
inline constexpr int kFormatFloat3 = 3;   // OIDN_FORMAT_FLOAT3
inline constexpr int kErrorNone = 0;      // OIDN_ERROR_NONE

struct Functions {
    Device (*new_device)(int type);
    void (*set_device_int)(Device, const char* name, int value);
    void (*commit_device)(Device);
    void (*release_device)(Device);
    int (*get_device_error)(Device, const char** message);
    Filter (*new_filter)(Device, const char* type);
    void (*set_shared_filter_image)(Filter, const char* name, void* data, int format,
                                    std::size_t width, std::size_t height, std::size_t byte_offset,
                                    std::size_t pixel_byte_stride, std::size_t row_byte_stride);
    void (*set_filter_bool)(Filter, const char* name, bool value);
    void (*commit_filter)(Filter);
    void (*execute_filter)(Filter);
    void (*release_filter)(Filter);
};

/// The library's functions, loaded once per path and kept for the process's life (OIDN's
/// own threads outlive a call). `path` "" searches as search_text() says. Throws
/// std::runtime_error saying where it looked and how to install OIDN.
const Functions& load(const std::string& path);

/// "$STATMC_OIDN_LIBRARY, libOpenImageDenoise.so.2 on the loader's path, pyoidn in
/// $VIRTUAL_ENV": the search order.
std::string search_text();

}  // namespace statmc::oidn_api
