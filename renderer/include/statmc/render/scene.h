// The renderable scene: Embree 3 geometry built from a SceneDescription, the materials
// and the lights, with the two ray queries the integrator needs.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "statmc/render/camera.h"
#include "statmc/render/lights.h"
#include "statmc/render/material.h"
#include "statmc/render/scene_description.h"

namespace statmc::render {

/// What the integrator needs to know about a ray's first hit.
struct SurfaceHit {
    float t = 0;
    Vec3 p;
    Vec3 ng;             ///< unit geometric normal, on the side of the shading normal (pbrt's rule)
    Vec3 ns;             ///< unit shading normal
    Vec3 dpdu;           ///< surface tangent along u (zero when the uvs are degenerate)
    float u = 0, v = 0;  ///< texture coordinates
    int material = 0;
    int emitter = -1;  ///< index into lights(), or −1
};

class Scene {
public:
    /// Builds Embree geometry for every shape. Throws std::runtime_error on Embree errors.
    explicit Scene(const SceneDescription& desc);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    std::optional<SurfaceHit> intersect(const Ray& ray) const;
    /// Whether anything blocks the segment origin + t·direction, t in (0, tmax).
    bool occluded(Vec3 origin, Vec3 direction, float tmax) const;

    const Lights& lights() const { return lights_; }
    const Material& material(int i) const { return materials_[std::size_t(i)]; }
    std::size_t triangle_count() const { return triangles_; }

    /// A ray origin just off surface point `p` (normal `ng`) on the side of `w`, so that
    /// a new ray does not hit the surface it leaves.
    static Vec3 offset_origin(Vec3 p, Vec3 ng, Vec3 w);

    /// Time stamp counter cycles spent inside Embree queries and the number of queries,
    /// summed over threads (for --profile: traversal vs shading). Off by default, since
    /// reading the counter around every ray costs a little.
    struct TraversalCounters {
        std::uint64_t cycles = 0;         ///< all queries
        std::uint64_t rays = 0;           ///< all queries
        std::uint64_t shadow_cycles = 0;  ///< the occlusion (shadow ray) queries among them
        std::uint64_t shadow_rays = 0;
    };
    void enable_profiling(bool on) { profiling_ = on; }
    bool profiling() const { return profiling_; }
    TraversalCounters traversal_counters() const;

private:
    struct Record;
    struct Embree;
    std::unique_ptr<Embree> embree_;
    std::vector<Record> records_;
    std::vector<Material> materials_;
    Lights lights_;
    std::size_t triangles_ = 0;
    bool profiling_ = false;
    mutable tbb::enumerable_thread_specific<TraversalCounters> counters_;
};

}  // namespace statmc::render
