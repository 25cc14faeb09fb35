#include "statmc/render/material.h"

#include <algorithm>
#include <cmath>

#include "statmc/render/bsdf.h"
#include "statmc/render/texture.h"

namespace statmc::render {

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
        return Bsdf(MetalLobe{m.eta, m.k, std::max(m.alpha_u, 1e-4f), std::max(m.alpha_v, 1e-4f)}, ns, ng, dpdu);
    case Material::Type::Glass:
        return Bsdf(GlassLobe{m.kr, m.kt, m.ior}, ns, ng, dpdu);
    case Material::Type::Mirror:
        return Bsdf(MirrorLobe{m.kr}, ns, ng, dpdu);
    }
    return Bsdf(MatteLobe{m.kd}, ns, ng, dpdu);
}

}  // namespace statmc::render
