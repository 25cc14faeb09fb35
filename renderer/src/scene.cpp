#include "statmc/render/scene.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <x86intrin.h>

#include <embree3/rtcore.h>

namespace statmc::render {

struct Scene::Record {
    ShapeDesc::Kind kind;
    std::shared_ptr<const TriangleMesh> mesh;
    Vec3 center;
    float radius = 0;
    bool flip = false;
    int material = 0;
    int emitter_base = -1;  ///< mesh: emitter of triangle i is base + i; sphere: its emitter
};

struct Scene::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string first_error;
    ~Embree()
    {
        if (scene)
            rtcReleaseScene(scene);
        if (device)
            rtcReleaseDevice(device);
    }
};

namespace {

void on_embree_error(void* user, RTCError, const char* message)
{
    auto* errors = static_cast<std::string*>(user);
    if (errors->empty())
        *errors = message ? message : "unknown Embree error";
}

// pbrt-v3's triangle normal: cross(p0 − p2, p1 − p2), turned towards the shading normals
// when the mesh has them, else flipped by ReverseOrientation / mirroring transforms.
Vec3 triangle_normal(const TriangleMesh& m, std::size_t tri, Vec3 shading)
{
    const Vec3& p0 = m.positions[m.indices[3 * tri]];
    const Vec3& p1 = m.positions[m.indices[3 * tri + 1]];
    const Vec3& p2 = m.positions[m.indices[3 * tri + 2]];
    Vec3 n = normalize(cross(p0 - p2, p1 - p2));
    if (!m.normals.empty())
        return face_forward(n, shading);
    return m.flip_normals ? -n : n;
}

}  // namespace

Scene::Scene(const SceneDescription& desc)
    : embree_(std::make_unique<Embree>()), materials_(desc.materials)
{
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device)
        throw std::runtime_error("cannot create the Embree device");
    rtcSetDeviceErrorFunction(embree_->device, on_embree_error, &embree_->first_error);
    embree_->scene = rtcNewScene(embree_->device);
    rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);

    for (const ShapeDesc& shape : desc.shapes) {
        Record rec{shape.kind,     shape.mesh, shape.center, shape.radius, shape.flip_normals,
                   shape.material, -1};
        RTCGeometry geom = nullptr;
        if (shape.kind == ShapeDesc::Kind::Sphere) {
            geom = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
            // New buffers are allocated (and padded for 16-byte loads) by Embree itself.
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
                geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 1));
            if (!v)
                throw std::runtime_error("Embree: " + embree_->first_error);
            v[0] = shape.center.x;
            v[1] = shape.center.y;
            v[2] = shape.center.z;
            v[3] = shape.radius;
            if (shape.emission) {
                Emitter e;
                e.kind = Emitter::Kind::Sphere;
                e.radiance = *shape.emission;
                e.two_sided = shape.two_sided;
                e.center = shape.center;
                e.radius = shape.radius;
                e.inward = shape.flip_normals;
                rec.emitter_base = lights_.add(e);
            }
        } else {
            const TriangleMesh& m = *shape.mesh;
            const std::size_t nv = m.positions.size(), nt = m.indices.size() / 3;
            geom = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
                geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
            auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
                geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
            if (!v || !idx)
                throw std::runtime_error("Embree: " + embree_->first_error);
            for (std::size_t i = 0; i < nv; ++i) {
                v[3 * i] = m.positions[i].x;
                v[3 * i + 1] = m.positions[i].y;
                v[3 * i + 2] = m.positions[i].z;
            }
            for (std::size_t i = 0; i < m.indices.size(); ++i)
                idx[i] = m.indices[i];
            triangles_ += nt;
            if (shape.emission) {
                for (std::size_t t = 0; t < nt; ++t) {
                    Emitter e;
                    e.kind = Emitter::Kind::Triangle;
                    e.radiance = *shape.emission;
                    e.two_sided = shape.two_sided;
                    e.p0 = m.positions[m.indices[3 * t]];
                    e.p1 = m.positions[m.indices[3 * t + 1]];
                    e.p2 = m.positions[m.indices[3 * t + 2]];
                    Vec3 avg;
                    if (!m.normals.empty())
                        avg = m.normals[m.indices[3 * t]] + m.normals[m.indices[3 * t + 1]] +
                              m.normals[m.indices[3 * t + 2]];
                    e.normal = triangle_normal(m, t, avg);
                    // Degenerate triangles stay (power 0: never chosen) to keep ids dense.
                    const int id = lights_.add(e);
                    if (rec.emitter_base < 0)
                        rec.emitter_base = id - int(t);
                }
            }
        }
        rtcCommitGeometry(geom);
        const unsigned id = rtcAttachGeometry(embree_->scene, geom);
        rtcReleaseGeometry(geom);
        if (id != records_.size())
            throw std::runtime_error("Embree: unexpected geometry id");
        records_.push_back(rec);
    }
    rtcCommitScene(embree_->scene);
    if (!embree_->first_error.empty())
        throw std::runtime_error("Embree: " + embree_->first_error);
    lights_.finish();
}

Scene::~Scene() = default;

Scene::TraversalCounters Scene::traversal_counters() const
{
    TraversalCounters total;
    for (const TraversalCounters& c : counters_) {
        total.cycles += c.cycles;
        total.rays += c.rays;
        total.shadow_cycles += c.shadow_cycles;
        total.shadow_rays += c.shadow_rays;
    }
    return total;
}

Vec3 Scene::offset_origin(Vec3 p, Vec3 ng, Vec3 w)
{
    const float scale =
        1e-4f * (1.f + std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
    return p + face_forward(ng, w) * scale;
}

std::optional<SurfaceHit> Scene::intersect(const Ray& ray) const
{
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    alignas(16) RTCRayHit rh;
    rh.ray.org_x = ray.origin.x;
    rh.ray.org_y = ray.origin.y;
    rh.ray.org_z = ray.origin.z;
    rh.ray.dir_x = ray.direction.x;
    rh.ray.dir_y = ray.direction.y;
    rh.ray.dir_z = ray.direction.z;
    rh.ray.tnear = 0.f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = ~0u;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (profiling_) {
        const std::uint64_t t0 = __rdtsc();
        rtcIntersect1(embree_->scene, &ctx, &rh);
        auto& c = counters_.local();
        c.cycles += __rdtsc() - t0;
        ++c.rays;
    } else {
        rtcIntersect1(embree_->scene, &ctx, &rh);
    }
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return std::nullopt;

    const Record& rec = records_[rh.hit.geomID];
    SurfaceHit hit;
    hit.t = rh.ray.tfar;
    hit.material = rec.material;
    if (rec.kind == ShapeDesc::Kind::Sphere) {
        hit.p = ray.origin + ray.direction * hit.t;
        Vec3 n = normalize(hit.p - rec.center);
        // Re-project onto the surface: removes the error of o + t·d far from the origin.
        hit.p = rec.center + n * rec.radius;
        if (rec.flip)
            n = -n;
        hit.ng = hit.ns = n;
        const Vec3 local = n;
        hit.dpdu = {-local.y, local.x, 0};  // along increasing φ about the z axis
        hit.u = (std::atan2(local.y, local.x) + kPi) / (2 * kPi);
        hit.v = std::acos(std::clamp(local.z, -1.f, 1.f)) * kInvPi;
        hit.emitter = rec.emitter_base;
        return hit;
    }
    const TriangleMesh& m = *rec.mesh;
    const std::size_t tri = rh.hit.primID;
    const std::uint32_t i0 = m.indices[3 * tri], i1 = m.indices[3 * tri + 1],
                        i2 = m.indices[3 * tri + 2];
    const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1 - b1 - b2;
    hit.p = m.positions[i0] * b0 + m.positions[i1] * b1 + m.positions[i2] * b2;
    Vec3 ns;
    if (!m.normals.empty()) {
        ns = normalize(m.normals[i0] * b0 + m.normals[i1] * b1 + m.normals[i2] * b2);
    }
    hit.ng = triangle_normal(m, tri, ns);
    hit.ns = (m.normals.empty() || length_squared(ns) == 0) ? hit.ng : ns;
    // pbrt-v3's default parameterisation when there are no uvs: (0,0), (1,0), (1,1).
    float uv[3][2] = {{0, 0}, {1, 0}, {1, 1}};
    if (!m.uvs.empty())
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t vi = k == 0 ? i0 : (k == 1 ? i1 : i2);
            uv[k][0] = m.uvs[2 * vi];
            uv[k][1] = m.uvs[2 * vi + 1];
        }
    hit.u = uv[0][0] * b0 + uv[1][0] * b1 + uv[2][0] * b2;
    hit.v = uv[0][1] * b0 + uv[1][1] * b1 + uv[2][1] * b2;
    // dp/du from the triangle's edges in position and uv (zero when the uvs degenerate).
    const float du02 = uv[0][0] - uv[2][0], dv02 = uv[0][1] - uv[2][1];
    const float du12 = uv[1][0] - uv[2][0], dv12 = uv[1][1] - uv[2][1];
    const float det = du02 * dv12 - dv02 * du12;
    if (std::abs(det) > 1e-12f) {
        const Vec3 dp02 = m.positions[i0] - m.positions[i2],
                   dp12 = m.positions[i1] - m.positions[i2];
        hit.dpdu = (dp02 * dv12 - dp12 * dv02) / det;
    }
    if (rec.emitter_base >= 0)
        hit.emitter = rec.emitter_base + int(tri);
    return hit;
}

bool Scene::occluded(Vec3 origin, Vec3 direction, float tmax) const
{
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    alignas(16) RTCRay ray;
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = 0.f;
    ray.tfar = tmax;
    ray.mask = ~0u;
    ray.flags = 0;
    ray.time = 0;
    if (profiling_) {
        const std::uint64_t t0 = __rdtsc();
        rtcOccluded1(embree_->scene, &ctx, &ray);
        auto& c = counters_.local();
        const std::uint64_t dt = __rdtsc() - t0;
        c.cycles += dt;
        c.shadow_cycles += dt;
        ++c.rays;
        ++c.shadow_rays;
    } else {
        rtcOccluded1(embree_->scene, &ctx, &ray);
    }
    return ray.tfar < 0;
}

}  // namespace statmc::render
