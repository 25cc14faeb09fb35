// Affine/projective 4x4 transforms as pbrt-v3 builds them: the current transformation
// matrix is post-multiplied by each directive, points are column vectors.
#pragma once

#include <array>
#include <cmath>
#include <optional>

#include "statmc/render/vec.h"

namespace statmc::render {

struct Transform {
    std::array<std::array<double, 4>, 4> m{
        {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};

    static Transform identity() { return {}; }
    /// pbrt's `Transform [16 numbers]`: the file lists the matrix column by column.
    static Transform from_pbrt(const double* v)
    {
        Transform t;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                t.m[r][c] = v[c * 4 + r];
        return t;
    }
    static Transform translate(Vec3 d)
    {
        Transform t;
        t.m[0][3] = d.x;
        t.m[1][3] = d.y;
        t.m[2][3] = d.z;
        return t;
    }
    static Transform scale(Vec3 s)
    {
        Transform t;
        t.m[0][0] = s.x;
        t.m[1][1] = s.y;
        t.m[2][2] = s.z;
        return t;
    }
    /// Rotation by `degrees` about `axis` (right-hand rule in pbrt's convention).
    static Transform rotate(double degrees, Vec3 axis)
    {
        const Vec3 a = normalize(axis);
        const double th = degrees * 3.14159265358979323846 / 180.0;
        const double s = std::sin(th), c = std::cos(th);
        Transform t;
        t.m[0][0] = a.x * a.x + (1 - a.x * a.x) * c;
        t.m[0][1] = a.x * a.y * (1 - c) - a.z * s;
        t.m[0][2] = a.x * a.z * (1 - c) + a.y * s;
        t.m[1][0] = a.x * a.y * (1 - c) + a.z * s;
        t.m[1][1] = a.y * a.y + (1 - a.y * a.y) * c;
        t.m[1][2] = a.y * a.z * (1 - c) - a.x * s;
        t.m[2][0] = a.x * a.z * (1 - c) - a.y * s;
        t.m[2][1] = a.y * a.z * (1 - c) + a.x * s;
        t.m[2][2] = a.z * a.z + (1 - a.z * a.z) * c;
        return t;
    }
    /// pbrt's LookAt: the world-to-camera transform of a camera at `eye` looking at `at`.
    static std::optional<Transform> look_at(Vec3 eye, Vec3 at, Vec3 up)
    {
        const Vec3 dir = normalize(at - eye);
        const Vec3 right0 = cross(normalize(up), dir);
        if (length(right0) == 0)
            return std::nullopt;
        const Vec3 right = normalize(right0);
        const Vec3 new_up = cross(dir, right);
        Transform camera_to_world;
        for (int r = 0; r < 3; ++r) {
            camera_to_world.m[r][0] = right[r];
            camera_to_world.m[r][1] = new_up[r];
            camera_to_world.m[r][2] = dir[r];
            camera_to_world.m[r][3] = eye[r];
        }
        return camera_to_world.inverse();
    }

    bool operator==(const Transform& o) const { return m == o.m; }

    Transform operator*(const Transform& o) const
    {
        Transform r;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                double s = 0;
                for (int k = 0; k < 4; ++k)
                    s += m[i][k] * o.m[k][j];
                r.m[i][j] = s;
            }
        return r;
    }

    /// The inverse by Gauss-Jordan elimination with partial pivoting; nullopt if singular.
    std::optional<Transform> inverse() const
    {
        auto a = m;
        Transform inv;
        for (int c = 0; c < 4; ++c) {
            int pivot = c;
            for (int r = c + 1; r < 4; ++r)
                if (std::abs(a[r][c]) > std::abs(a[pivot][c]))
                    pivot = r;
            if (std::abs(a[pivot][c]) < 1e-300)
                return std::nullopt;
            std::swap(a[c], a[pivot]);
            std::swap(inv.m[c], inv.m[pivot]);
            const double d = 1.0 / a[c][c];
            for (int k = 0; k < 4; ++k) {
                a[c][k] *= d;
                inv.m[c][k] *= d;
            }
            for (int r = 0; r < 4; ++r) {
                if (r == c)
                    continue;
                const double f = a[r][c];
                for (int k = 0; k < 4; ++k) {
                    a[r][k] -= f * a[c][k];
                    inv.m[r][k] -= f * inv.m[c][k];
                }
            }
        }
        return inv;
    }

    Vec3 point(Vec3 p) const
    {
        double r[4];
        for (int i = 0; i < 4; ++i)
            r[i] = m[i][0] * p.x + m[i][1] * p.y + m[i][2] * p.z + m[i][3];
        const double w = r[3] != 0 ? r[3] : 1.0;
        return {float(r[0] / w), float(r[1] / w), float(r[2] / w)};
    }
    Vec3 vector(Vec3 v) const
    {
        return {float(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z),
                float(m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z),
                float(m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z)};
    }
    /// Normals transform with the inverse transpose (`inv` is this transform's inverse).
    static Vec3 normal(const Transform& inv, Vec3 n)
    {
        return {float(inv.m[0][0] * n.x + inv.m[1][0] * n.y + inv.m[2][0] * n.z),
                float(inv.m[0][1] * n.x + inv.m[1][1] * n.y + inv.m[2][1] * n.z),
                float(inv.m[0][2] * n.x + inv.m[1][2] * n.y + inv.m[2][2] * n.z)};
    }
    /// Whether the transform mirrors space (negative determinant of the 3x3 part), which
    /// flips the orientation of triangles (pbrt's TransformSwapsHandedness).
    bool swaps_handedness() const
    {
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        return det < 0;
    }
};

}  // namespace statmc::render
