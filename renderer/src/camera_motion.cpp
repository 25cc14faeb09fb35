// Camera animation for sequences (pbrt-v3's ActiveTransform/TransformTimes, reduced to
// what a pan or a dolly needs): the end pose is the start pose turned by a rotation R and
// moved by a translation, and at fraction s of the way the camera has turned by R^s (the
// same axis, s times the angle) and moved by s times the translation. pbrt-v3 decomposes
// and slerps instead; for a rigid motion both give the same poses, and this form also
// keeps a handedness flip (Scale -1 1 1) that a decomposition into a quaternion would lose.
#include <algorithm>
#include <array>
#include <cmath>

#include "statmc/render/scene_description.h"
#include "statmc/render/scene_error.h"

namespace statmc::render {

namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

Matrix3 linear_part(const Transform& t)
{
    Matrix3 m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            m[r][c] = t.m[r][c];
    return m;
}

Matrix3 multiply(const Matrix3& a, const Matrix3& b)
{
    Matrix3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                r[i][j] += a[i][k] * b[k][j];
    return r;
}

Matrix3 transposed(const Matrix3& a)
{
    Matrix3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[i][j] = a[j][i];
    return r;
}

double determinant(const Matrix3& a)
{
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

struct CameraToWorld {
    Transform start, end;
};

CameraToWorld camera_to_world(const CameraDesc& camera)
{
    const auto start = camera.world_to_camera.inverse();
    const auto end = camera.world_to_camera_end.inverse();
    if (!start || !end)
        throw SceneError("the camera transform is singular");
    return {*start, *end};
}

// R = L_end · L_start⁻¹: the rotation from the start pose to the end pose, in world space.
std::optional<Matrix3> relative_rotation(const CameraToWorld& c)
{
    const auto inv = c.start.inverse();  // its linear part is l0⁻¹ for an affine transform
    if (!inv)
        return std::nullopt;
    const Matrix3 r = multiply(linear_part(c.end), linear_part(*inv));
    const Matrix3 rrt = multiply(r, transposed(r));
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(rrt[i][j] - (i == j ? 1.0 : 0.0)) > 1e-4)
                return std::nullopt;
    if (determinant(r) <= 0)
        return std::nullopt;
    return r;
}

// The rotation by `angle` about the unit `axis` (Rodrigues).
Matrix3 rotation(const double axis[3], double angle)
{
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const double x = axis[0], y = axis[1], z = axis[2];
    return {{{t * x * x + c, t * x * y - s * z, t * x * z + s * y},
             {t * x * y + s * z, t * y * y + c, t * y * z - s * x},
             {t * x * z - s * y, t * y * z + s * x, t * z * z + c}}};
}

// R^s for a proper rotation R: its axis, s times its angle.
Matrix3 fractional_rotation(const Matrix3& r, double s)
{
    const double cos_angle = std::clamp((r[0][0] + r[1][1] + r[2][2] - 1) / 2, -1.0, 1.0);
    const double angle = std::acos(cos_angle);
    if (angle < 1e-12)
        return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    double axis[3] = {r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]};
    double norm = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (norm < 1e-9) {
        // A half turn: the axis is the column of (R + I)/2 with the largest norm.
        int best = 0;
        for (int k = 1; k < 3; ++k)
            if (r[k][k] > r[best][best])
                best = k;
        for (int k = 0; k < 3; ++k)
            axis[k] = (r[k][best] + (k == best ? 1.0 : 0.0)) / 2;
        norm = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    }
    for (double& a : axis)
        a /= norm;
    return rotation(axis, s * angle);
}

}  // namespace

bool camera_motion_is_rigid(const CameraDesc& camera)
{
    return relative_rotation(camera_to_world(camera)).has_value();
}

CameraDesc CameraDesc::at_time(double time) const
{
    CameraDesc at = *this;
    if (!animated())
        return at;
    const double s = std::clamp((time - start_time) / (end_time - start_time), 0.0, 1.0);
    const CameraToWorld c = camera_to_world(*this);
    const auto r = relative_rotation(c);
    if (!r)
        throw SceneError("the camera's start and end transforms differ by more than a rotation "
                         "and a translation");
    const Matrix3 l = multiply(fractional_rotation(*r, s), linear_part(c.start));
    Transform pose;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j)
            pose.m[i][j] = l[i][j];
        pose.m[i][3] = c.start.m[i][3] + s * (c.end.m[i][3] - c.start.m[i][3]);
    }
    const auto world_to_camera = pose.inverse();
    if (!world_to_camera)
        throw SceneError("the camera transform is singular");
    at.world_to_camera = at.world_to_camera_end = *world_to_camera;
    return at;
}

}  // namespace statmc::render
