// The pbrt-v3 subset statmc-render reads (see README in renderer/): transforms, camera,
// film, sampler/integrator settings, materials, image textures, diffuse area lights and
// trianglemesh / plymesh / sphere shapes. Unknown directives and parameters are warnings
// naming file:line; malformed input is a SceneError naming file:line.
#pragma once

#include <string>

#include "statmc/render/scene_description.h"
#include "statmc/render/scene_error.h"

namespace statmc::render {

/// Parses the scene file at `path`; relative mesh and texture names resolve against its
/// directory.
SceneDescription parse_scene_file(const std::string& path);

/// Parses scene text; `file` names it in messages and `directory` resolves relative paths.
SceneDescription parse_scene_string(const std::string& text, const std::string& file,
                                    const std::string& directory = ".");

}  // namespace statmc::render
