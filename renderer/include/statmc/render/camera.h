// pbrt-v3's perspective camera: the field of view spans the shorter image axis, raster
// y grows downwards, camera space looks down +z with +y up.
#pragma once

#include "statmc/render/ray.h"
#include "statmc/render/scene_description.h"
#include "statmc/render/vec.h"

namespace statmc::render {

class Camera {
public:
    /// The camera of `desc` rendering `width` x `height` pixels (a resolution override
    /// keeps the fov on the shorter axis, as pbrt does). Throws SceneError when the
    /// camera transform is singular.
    Camera(const CameraDesc& desc, int width, int height);

    /// The ray through raster position (x, y) in pixels, (0, 0) the top-left corner.
    Ray generate(float x, float y) const;
    /// Where this camera sees world point `p`, in raster pixels (generate's inverse);
    /// false when p is not in front of it.
    bool raster(Vec3 p, float& x, float& y) const;
    Vec3 forward() const { return forward_; }

private:
    Transform camera_to_world_, world_to_camera_;
    Vec3 origin_, forward_;
    float tan_half_fov_;
    float screen_x_, screen_y_;  ///< half extents of the screen window
    int width_, height_;
};

}  // namespace statmc::render
