// PLY meshes as pbrt's "plymesh" uses them: vertex x,y,z with optional normals (nx,ny,nz)
// and uvs (u,v / s,t / texture_u,texture_v), faces as index lists (triangles and quads).
// ASCII and binary (both endiannesses).
#pragma once

#include <string>

#include "statmc/render/scene_description.h"

namespace statmc::render {

/// Reads `path` into an object-space mesh. Throws std::runtime_error naming the file.
TriangleMesh read_ply(const std::string& path);

}  // namespace statmc::render
