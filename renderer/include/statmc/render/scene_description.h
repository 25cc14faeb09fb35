// What the parser produces: a flat, world-space description of the scene (camera, render
// settings, materials, shapes). Nothing here knows about Embree; scene.h builds on it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "statmc/render/material.h"
#include "statmc/render/transform.h"
#include "statmc/render/vec.h"

namespace statmc::render {

/// Triangles in world space. Normals and uvs are optional (empty when absent).
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<float> uvs;  ///< two per vertex
    std::vector<std::uint32_t> indices;
    /// ReverseOrientation xor a handedness-swapping transform: flips the geometric normal
    /// of meshes without shading normals (pbrt-v3's rule), and so the side a light emits to.
    bool flip_normals = false;
};

struct ShapeDesc {
    enum class Kind { Mesh, Sphere };
    Kind kind = Kind::Mesh;
    std::shared_ptr<const TriangleMesh> mesh;
    Vec3 center;                ///< sphere
    float radius = 1;           ///< sphere
    bool flip_normals = false;  ///< sphere: emit inward
    int material = 0;
    std::optional<Rgb> emission;  ///< AreaLightSource "diffuse" L
    bool two_sided = false;       ///< AreaLightSource "bool twosided"
    std::string where;            ///< file:line of the Shape directive, for messages
};

struct CameraDesc {
    Transform world_to_camera;      ///< at start_time
    Transform world_to_camera_end;  ///< at end_time (ActiveTransform EndTime)
    double start_time = 0, end_time = 1;  ///< TransformTimes
    float fov_degrees = 90;  ///< on the shorter image axis, as pbrt-v3
    int width = 640;
    int height = 480;

    bool animated() const { return !(world_to_camera == world_to_camera_end); }
    /// The camera at `time`: the start and end poses interpolated rigidly (the rotation
    /// between them at a constant angular rate, the position linearly), held before
    /// start_time and after end_time.
    CameraDesc at_time(double time) const;
};

/// Whether the camera's end pose is its start pose moved by a rotation and a translation
/// (what at_time can interpolate).
bool camera_motion_is_rigid(const CameraDesc& camera);

struct SceneDescription {
    std::string file;
    CameraDesc camera;
    /// Where the resolution came from, for messages: "file:line: Film", or the file alone
    /// when it has no Film directive (640×480).
    std::string film_where;
    int spp = 16;                     ///< Sampler "integer pixelsamples"
    int maxdepth = 5;                 ///< Integrator "integer maxdepth" (pbrt-v3's default 5)
    std::vector<Material> materials;  ///< [0] is the default matte
    std::vector<ShapeDesc> shapes;
    std::vector<std::string> warnings;  ///< "file:line: warning: ..."
    /// CRC-32 of the scene text and its Includes' in reading order (meshes are not read
    /// here): what a checkpoint checks to refuse another scene's.
    std::uint32_t source_crc = 0;
};

}  // namespace statmc::render
