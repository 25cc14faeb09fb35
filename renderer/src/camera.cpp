#include "statmc/render/camera.h"

#include <cmath>

#include "statmc/render/scene_error.h"

namespace statmc::render {

Camera::Camera(const CameraDesc& desc, int width, int height) : width_(width), height_(height)
{
    const auto inv = desc.world_to_camera.inverse();
    if (!inv)
        throw SceneError("the camera transform is singular");
    camera_to_world_ = *inv;
    world_to_camera_ = desc.world_to_camera;
    origin_ = camera_to_world_.point({0, 0, 0});
    forward_ = normalize(camera_to_world_.vector({0, 0, 1}));
    tan_half_fov_ = std::tan(desc.fov_degrees * kPi / 360.f);
    const float aspect = float(width) / float(height);
    screen_x_ = aspect > 1 ? aspect : 1.f;
    screen_y_ = aspect > 1 ? 1.f : 1.f / aspect;
}

Ray Camera::generate(float x, float y) const
{
    const float sx = -screen_x_ + 2 * screen_x_ * (x / float(width_));
    const float sy = screen_y_ - 2 * screen_y_ * (y / float(height_));
    const Vec3 d_camera{sx * tan_half_fov_, sy * tan_half_fov_, 1.f};
    return {origin_, normalize(camera_to_world_.vector(d_camera))};
}

bool Camera::raster(Vec3 p, float& x, float& y) const
{
    const Vec3 c = world_to_camera_.point(p);
    if (!(c.z > 1e-6f))
        return false;
    const float sx = c.x / (c.z * tan_half_fov_), sy = c.y / (c.z * tan_half_fov_);
    x = (sx + screen_x_) / (2 * screen_x_) * float(width_);
    y = (screen_y_ - sy) / (2 * screen_y_) * float(height_);
    return std::isfinite(x) && std::isfinite(y);
}

}  // namespace statmc::render
