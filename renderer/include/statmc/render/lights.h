// Diffuse area lights (pbrt-v3 "diffuse"): constant radiance L leaving the side the
// surface normal points to (both sides when twosided). Each emissive triangle and sphere
// is one emitter; an emitter is chosen in proportion to its power (luminance · area),
// then a point on it: uniformly by area on a triangle, uniformly in the subtended cone
// for a sphere seen from outside (far less noise for the small spheres of Veach MIS).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "statmc/render/vec.h"

namespace statmc::render {

struct Emitter {
    enum class Kind { Triangle, Sphere };
    Kind kind = Kind::Triangle;
    Rgb radiance;
    bool two_sided = false;
    Vec3 p0, p1, p2;  ///< triangle
    Vec3 normal;      ///< triangle: the oriented geometric normal (emitting side)
    Vec3 center;      ///< sphere
    float radius = 0;
    bool inward = false;  ///< sphere: ReverseOrientation, emits towards its centre

    float area() const;
    float cached_area = 0;  ///< area(), set by Lights::finish
    /// Radiance leaving point `p` with normal `n` (oriented as this emitter's) towards `w`.
    Rgb emitted(Vec3 n, Vec3 w) const;
};

struct LightSample {
    Vec3 wi;         ///< unit direction from the shading point to the light
    float distance;  ///< to the sampled point
    Rgb radiance;    ///< emitted towards the shading point (0 from the back side)
    float pdf;       ///< solid angle density at the shading point, emitter choice included
};

class Lights {
public:
    /// Returns the index of the added emitter.
    int add(const Emitter& e);
    /// Builds the selection distribution; call once after the last add.
    void finish();
    bool empty() const { return emitters_.empty(); }
    const Emitter& emitter(int i) const { return emitters_[std::size_t(i)]; }

    std::optional<LightSample> sample(Vec3 p, float u_select, float u1, float u2) const;
    /// Solid angle pdf with which sample() from `p` produces the point `q` on emitter `i`
    /// with normal `n` (for the MIS weight of a BSDF-sampled hit).
    float pdf(Vec3 p, int i, Vec3 q, Vec3 n) const;

private:
    std::vector<Emitter> emitters_;
    std::vector<float> cdf_;  ///< normalized, cdf_.back() == 1
    std::vector<float> prob_;
};

}  // namespace statmc::render
