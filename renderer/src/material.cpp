#include "statmc/render/material.h"

#include <algorithm>
#include <cmath>

#include "statmc/render/bsdf.h"
#include "statmc/render/parameter_list.h"
#include "statmc/render/texture.h"

namespace statmc::render {

namespace {

/// "matte": Kd as an rgb or an imagemap texture; sigma (Oren-Nayar) is read and warned about.
Material read_matte(ParameterList& ps, const NamedTextures& textures,
                    std::vector<std::string>& warnings)
{
    Material m;
    m.type = Material::Type::Matte;
    if (const Parameter* t = ps.find("texture", "Kd")) {
        const auto it = t->strings.size() == 1 ? textures.find(t->strings[0]) : textures.end();
        if (it == textures.end())
            ps.error(t->line, "texture \"" + (t->strings.empty() ? "" : t->strings[0]) +
                                  "\" was not defined");
        m.kd_texture = it->second;
    } else if (auto kd = ps.get_rgb("Kd")) {
        m.kd = *kd;
    }
    if (ps.get_float("sigma").value_or(0.f) != 0.f)
        warnings.push_back(
            ps.warning("matte \"float sigma\" (Oren-Nayar) not supported, rendered as Lambertian"));
    return m;
}

/// "metal": eta, k and roughness (isotropic or u/v), remapped to alphas by default.
Material read_metal(ParameterList& ps)
{
    Material m;
    m.type = Material::Type::Metal;
    if (auto e = ps.get_rgb("eta"))
        m.eta = *e;
    if (auto k = ps.get_rgb("k"))
        m.k = *k;
    const float rough = ps.get_float("roughness").value_or(0.01f);
    float u = ps.get_float("uroughness").value_or(rough),
          v = ps.get_float("vroughness").value_or(rough);
    if (ps.get_bool("remaproughness").value_or(true)) {
        u = roughness_to_alpha(u);
        v = roughness_to_alpha(v);
    }
    m.alpha_u = u;
    m.alpha_v = v;
    return m;
}

/// "glass": Kr, Kt and index; only zero roughness is supported.
Material read_glass(ParameterList& ps)
{
    Material m;
    m.type = Material::Type::Glass;
    if (auto kr = ps.get_rgb("Kr"))
        m.kr = *kr;
    if (auto kt = ps.get_rgb("Kt"))
        m.kt = *kt;
    m.ior = ps.get_float("index").value_or(1.5f);
    const float rough = ps.get_float("roughness").value_or(0.f);
    if (ps.get_float("uroughness").value_or(rough) != 0.f ||
        ps.get_float("vroughness").value_or(rough) != 0.f)
        ps.error("unsupported: rough glass (only smooth dielectrics)");
    ps.get_bool("remaproughness");  // checked; meaningless without roughness
    return m;
}

/// "mirror": Kr, 0.9 by default as in pbrt-v3.
Material read_mirror(ParameterList& ps)
{
    Material m;
    m.type = Material::Type::Mirror;
    m.kr = Rgb{0.9f};
    if (auto kr = ps.get_rgb("Kr"))
        m.kr = *kr;
    return m;
}

}  // namespace

Material read_material(const std::string& type, const std::string& name, ParameterList& ps,
                       const NamedTextures& textures, std::vector<std::string>& warnings)
{
    Material m;
    if (type == "matte")
        m = read_matte(ps, textures, warnings);
    else if (type == "metal")
        m = read_metal(ps);
    else if (type == "glass")
        m = read_glass(ps);
    else if (type == "mirror")
        m = read_mirror(ps);
    else if (type == "" || type == "none")
        ps.error("unsupported: material \"none\"");
    else
        ps.error("unsupported: material \"" + type + "\" (supported: matte, metal, glass, mirror)");
    m.name = name;
    return m;
}

float roughness_to_alpha(float roughness)
{
    const float x = std::log(std::max(roughness, 1e-3f));
    return 1.62142f + 0.819955f * x + 0.1734f * x * x + 0.0171201f * x * x * x +
           0.000640711f * x * x * x * x;
}

Bsdf material_bsdf(const Material& m, Vec3 ns, Vec3 ng, Vec3 dpdu, float u, float v)
{
    switch (m.type) {
    case Material::Type::Matte: {
        Rgb kd = m.kd_texture ? m.kd_texture->lookup(u, v) : m.kd;
        kd = {std::clamp(kd.r, 0.f, 1.f), std::clamp(kd.g, 0.f, 1.f), std::clamp(kd.b, 0.f, 1.f)};
        return Bsdf(MatteLobe{kd}, ns, ng, dpdu);
    }
    case Material::Type::Metal:
        return Bsdf(MetalLobe{m.eta, m.k, std::max(m.alpha_u, 1e-4f), std::max(m.alpha_v, 1e-4f)},
                    ns, ng, dpdu);
    case Material::Type::Glass:
        return Bsdf(GlassLobe{m.kr, m.kt, m.ior}, ns, ng, dpdu);
    case Material::Type::Mirror:
        return Bsdf(MirrorLobe{m.kr}, ns, ng, dpdu);
    }
    return Bsdf(MatteLobe{m.kd}, ns, ng, dpdu);
}

}  // namespace statmc::render
