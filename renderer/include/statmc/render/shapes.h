// The shapes of pbrt-v3's Shape directive that the renderer supports ("sphere",
// "trianglemesh", "plymesh"): each reads its own parameters and is placed in world space
// once, at parse time (every later stage works in world coordinates).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "statmc/render/scene_description.h"
#include "statmc/render/transform.h"

namespace statmc::render {

class ParameterList;

/// The object-space mesh of a plymesh's "string filename" (resolved, read and cached by
/// the caller, which also reports a file that cannot be read).
using PlyLoader = std::function<std::shared_ptr<const TriangleMesh>(const std::string& filename)>;

/// The shape of `Shape "<type>"` with parameters `ps`, under the current transform
/// `object_to_world` and ReverseOrientation state. Sets the geometry (kind, mesh or
/// centre and radius, flip_normals); material, emission, two_sided and where are the
/// caller's. Parameters not supported but harmless are marked used, with a warning
/// appended to `warnings`; unknown ones are left unused for the caller to report.
/// Errors (unsupported shape, bad values, a singular transform) are SceneErrors at
/// file:line.
ShapeDesc read_shape(const std::string& type, ParameterList& ps, const Transform& object_to_world,
                     bool reverse_orientation, const PlyLoader& load_ply,
                     std::vector<std::string>& warnings);

}  // namespace statmc::render
