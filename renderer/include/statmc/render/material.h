// The pbrt-v3 materials the renderer supports, as parameters; material.cpp reads one from
// its directive's parameters and turns one into the BSDF at a surface point.
#pragma once

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "statmc/render/vec.h"

namespace statmc::render {

class ImageTexture;
class Bsdf;
class ParameterList;

struct Material {
    enum class Type { Matte, Metal, Glass, Mirror };
    Type type = Type::Matte;
    std::string name;
    // matte
    Rgb kd{0.5f};
    std::shared_ptr<const ImageTexture> kd_texture;  ///< replaces kd when set
    // metal: conductor Fresnel (eta, k) and Trowbridge-Reitz alphas (already remapped)
    Rgb eta{0.2004f, 0.9240f, 1.1022f};  // pbrt-v3's default: copper
    Rgb k{3.9129f, 2.4528f, 2.1421f};
    float alpha_u = 0.01f, alpha_v = 0.01f;
    // glass (smooth dielectric) and mirror
    Rgb kr{1.f}, kt{1.f};
    float ior = 1.5f;
};

/// Image textures by the name their Texture directive gave them.
using NamedTextures = std::unordered_map<std::string, std::shared_ptr<const ImageTexture>>;

/// The material of pbrt-v3 type `type` ("matte", "metal", "glass" or "mirror"), called
/// `name`, from its Material / MakeNamedMaterial parameters `ps` ("texture Kd" looks up
/// `textures`). Each type reads its own parameters, with pbrt-v3's defaults; warnings
/// (a feature read but not rendered) are appended to `warnings`, and parameters it does
/// not know are left unused for the caller to report. Unsupported types or values are
/// SceneErrors at file:line.
Material read_material(const std::string& type, const std::string& name, ParameterList& ps,
                       const NamedTextures& textures, std::vector<std::string>& warnings);

/// pbrt-v3's TrowbridgeReitzDistribution::RoughnessToAlpha (a polynomial fit in log r),
/// applied when a metal says "bool remaproughness" true (its default).
float roughness_to_alpha(float roughness);

/// The BSDF of `material` at a point with shading normal `ns`, geometric normal `ng`
/// (both unit, same side), tangent dp/du (orients anisotropic roughness; zero: any)
/// and texture coordinates (u, v).
Bsdf material_bsdf(const Material& material, Vec3 ns, Vec3 ng, Vec3 dpdu, float u, float v);

}  // namespace statmc::render
