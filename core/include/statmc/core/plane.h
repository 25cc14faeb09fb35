// Strided views of one float image plane: how core reads and writes pixels it does not own.
#pragma once

#include <cstddef>

namespace statmc {

/// A read-only view of one channel: element (x, y) is data[x*xstride + y*ystride].
/// Strides are in floats, so an interleaved RGB buffer gives three planes with xstride 3.
struct ConstPlane {
    const float* data = nullptr;
    std::ptrdiff_t xstride = 1;
    std::ptrdiff_t ystride = 0;

    float operator()(int x, int y) const { return data[x * xstride + y * ystride]; }
    explicit operator bool() const { return data != nullptr; }
};

/// A writable view of one channel, laid out as ConstPlane.
struct Plane {
    float* data = nullptr;
    std::ptrdiff_t xstride = 1;
    std::ptrdiff_t ystride = 0;

    float& operator()(int x, int y) const { return data[x * xstride + y * ystride]; }
    explicit operator bool() const { return data != nullptr; }
    operator ConstPlane() const { return {data, xstride, ystride}; }
};

/// A dense single-channel plane of width w: xstride 1, ystride w.
inline ConstPlane dense_plane(const float* data, int width) { return {data, 1, width}; }
inline Plane dense_plane(float* data, int width) { return {data, 1, width}; }

}  // namespace statmc
