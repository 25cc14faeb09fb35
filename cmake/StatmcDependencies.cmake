# All dependencies come from Debian 12 packages (scripts/install-deps.sh installs them).
find_package(TBB CONFIG REQUIRED)
find_package(Boost 1.74 REQUIRED)   # header-only Boost.Math

if(NOT STATMC_CORE_ONLY)
find_package(OpenImageIO 2.4 CONFIG REQUIRED)
# OIIO's exported target lists /usr/include/opencv4 even when OpenCV is absent.
get_target_property(_statmc_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
list(FILTER _statmc_oiio_inc EXCLUDE REGEX "opencv4")
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_statmc_oiio_inc}")
find_package(OpenEXR 3 CONFIG REQUIRED)
find_package(Imath 3 CONFIG REQUIRED)
# OCIO's own CMake config is broken on Debian 12 (wrong include dir); pkg-config works.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO>=2.1)
# The renderer (renderer/): Embree 3 for rays, CLI11 for its command line.
find_package(embree 3.13 CONFIG REQUIRED)   # target `embree` (no namespace)
find_package(CLI11 CONFIG REQUIRED)
find_package(ZLIB REQUIRED)         # CRC-32 of render checkpoints
endif()

if(STATMC_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
if(STATMC_BUILD_BENCH)
  find_package(benchmark CONFIG REQUIRED)
endif()
