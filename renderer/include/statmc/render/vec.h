// Small value types of the renderer: 3-vectors for geometry and RGB triples for radiance.
// Kept separate (Vec3 vs Rgb) so that a colour is never used as a direction by accident.
#pragma once

#include <algorithm>
#include <cmath>

#include "statmc/core/luminance.h"

namespace statmc::render {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 1.f / kPi;

struct Vec3 {
    float x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(float s, Vec3 a) { return a * s; }
inline Vec3 operator/(Vec3 a, float s) { return a * (1.f / s); }
inline Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length_squared(Vec3 a) { return dot(a, a); }
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a)
{
    const float l = length(a);
    return l > 0 ? a / l : a;
}
/// `n` flipped, if needed, into the hemisphere of `v`.
inline Vec3 face_forward(Vec3 n, Vec3 v) { return dot(n, v) < 0 ? -n : n; }

/// An orthonormal basis around a unit normal (Duff et al. 2017, branchless), in which
/// BSDFs work with z = normal.
struct Frame {
    Vec3 s, t, n;

    static Frame from_normal(Vec3 n)
    {
        const float sign = std::copysign(1.f, n.z);
        const float a = -1.f / (sign + n.z);
        const float b = n.x * n.y * a;
        return {{1.f + sign * n.x * n.x * a, sign * b, -sign * n.x},
                {b, sign + n.y * n.y * a, -n.y},
                n};
    }
    /// The frame around `n` whose s axis is `tangent` made orthogonal to n (pbrt's
    /// shading frame, s along dp/du, so that anisotropic roughness follows the texture
    /// parameterisation); any frame when the tangent is zero or parallel to n.
    static Frame from_normal_tangent(Vec3 n, Vec3 tangent)
    {
        const Vec3 s0 = tangent - n * dot(n, tangent);
        const float l = length(s0);
        if (!(l > 1e-6f * length(tangent)) || !(l > 0))
            return from_normal(n);
        const Vec3 s = s0 / l;
        return {s, cross(n, s), n};
    }
    Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

struct Rgb {
    float r = 0, g = 0, b = 0;

    constexpr Rgb() = default;
    constexpr explicit Rgb(float v) : r(v), g(v), b(v) {}
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    bool is_black() const { return r == 0 && g == 0 && b == 0; }
    float max_component() const { return std::max(r, std::max(g, b)); }
    /// Luminance (core/luminance.h).
    float luminance() const { return statmc::luminance(r, g, b); }
};

inline Rgb operator+(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline Rgb operator-(Rgb a, Rgb b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
inline Rgb operator*(Rgb a, Rgb b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
inline Rgb operator*(Rgb a, float s) { return {a.r * s, a.g * s, a.b * s}; }
inline Rgb operator*(float s, Rgb a) { return a * s; }
inline Rgb operator/(Rgb a, float s) { return a * (1.f / s); }
inline Rgb& operator+=(Rgb& a, Rgb b) { return a = a + b; }
inline Rgb& operator*=(Rgb& a, Rgb b) { return a = a * b; }
inline Rgb& operator*=(Rgb& a, float s) { return a = a * s; }

}  // namespace statmc::render
