#include "statmc/render/shapes.h"

#include <cmath>
#include <cstdint>
#include <utility>

#include "statmc/render/parameter_list.h"

namespace statmc::render {

namespace {

/// pbrt's full sphere "float radius" (default 1) around the object-space origin. Only
/// uniform scales keep it a sphere; ReverseOrientation makes it emit inwards.
ShapeDesc sphere(ParameterList& ps, const Transform& ctm, bool reverse_orientation)
{
    const float r = ps.get_float("radius").value_or(1.f);
    if (!(r > 0))
        ps.error("sphere radius must be positive");
    for (const char* partial : {"zmin", "zmax", "phimax"})
        if (const Parameter* p = ps.find_any(partial))
            ps.error(p->line, std::string("unsupported: partial sphere (\"") + partial + "\")");
    ShapeDesc s;
    s.kind = ShapeDesc::Kind::Sphere;
    s.center = ctm.point({0, 0, 0});
    const Vec3 ax = ctm.vector({1, 0, 0}), ay = ctm.vector({0, 1, 0}), az = ctm.vector({0, 0, 1});
    const float sx = length(ax), sy = length(ay), sz = length(az);
    if (std::abs(sx - sy) > 1e-4f * sx || std::abs(sx - sz) > 1e-4f * sx)
        ps.error("unsupported: non-uniformly scaled sphere");
    s.radius = r * sx;
    s.flip_normals = reverse_orientation;
    return s;
}

/// pbrt's "trianglemesh": "point P", "integer indices" (optional for a single
/// triangle), optional "normal N" and uvs ("float uv", "float st" or "point2 uv"), in
/// object space.
TriangleMesh trianglemesh(ParameterList& ps, std::vector<std::string>& warnings)
{
    TriangleMesh mesh;
    const Parameter* idx = ps.find("integer", "indices");
    const Parameter* P = ps.find("point", "P");
    if (!P)
        ps.error("trianglemesh needs \"point P\"");
    if (P->numbers.size() % 3 != 0)
        ps.error(P->line, "\"point P\" needs a multiple of 3 values");
    for (std::size_t i = 0; i < P->numbers.size(); i += 3)
        mesh.positions.push_back(
            {float(P->numbers[i]), float(P->numbers[i + 1]), float(P->numbers[i + 2])});
    if (idx) {
        if (idx->numbers.size() % 3 != 0 || idx->numbers.empty())
            ps.error(idx->line, "\"integer indices\" needs a positive multiple of 3 values");
        for (double v : idx->numbers) {
            // NaN and fractions fail too: only a whole number names a vertex.
            if (!(v >= 0 && v < double(mesh.positions.size()) && v == std::floor(v)))
                ps.error(idx->line, "index " + number_text(v) + " out of range (" +
                                        std::to_string(mesh.positions.size()) + " vertices)");
            mesh.indices.push_back(std::uint32_t(v));
        }
    } else if (mesh.positions.size() == 3) {
        mesh.indices = {0, 1, 2};
    } else {
        ps.error("trianglemesh needs \"integer indices\"");
    }
    if (const Parameter* N = ps.find("normal", "N")) {
        if (N->numbers.size() != P->numbers.size())
            ps.error(N->line, "\"normal N\" must have as many values as \"point P\"");
        for (std::size_t i = 0; i < N->numbers.size(); i += 3)
            mesh.normals.push_back(
                {float(N->numbers[i]), float(N->numbers[i + 1]), float(N->numbers[i + 2])});
    }
    const Parameter* uv = ps.find("float", "uv");
    if (!uv)
        uv = ps.find("float", "st");
    if (!uv)
        uv = ps.find("point2", "uv");
    if (uv) {
        if (uv->numbers.size() != mesh.positions.size() * 2)
            ps.error(uv->line, "\"" + uv->type + " " + uv->name + "\" needs 2 values per vertex");
        for (double v : uv->numbers)
            mesh.uvs.push_back(float(v));
    }
    for (std::string& w : ps.ignore({"S", "alpha", "shadowalpha"}, "trianglemesh"))
        warnings.push_back(std::move(w));
    return mesh;
}

/// pbrt's "plymesh": the PLY file named by "string filename", in object space.
TriangleMesh plymesh(ParameterList& ps, const PlyLoader& load_ply)
{
    const std::string filename = ps.get_string("filename").value_or("");
    if (filename.empty())
        ps.error("plymesh needs \"string filename\"");
    return *load_ply(filename);
}

}  // namespace

ShapeDesc read_shape(const std::string& type, ParameterList& ps, const Transform& object_to_world,
                     bool reverse_orientation, const PlyLoader& load_ply,
                     std::vector<std::string>& warnings)
{
    const auto inv = object_to_world.inverse();
    if (!inv)
        ps.error("the current transform is singular");
    if (type == "sphere")
        return sphere(ps, object_to_world, reverse_orientation);
    if (type != "trianglemesh" && type != "plymesh")
        ps.error("unsupported: Shape \"" + type + "\" (supported: trianglemesh, plymesh, sphere)");

    TriangleMesh mesh = type == "trianglemesh" ? trianglemesh(ps, warnings) : plymesh(ps, load_ply);
    // To world space, once: every later stage works in world coordinates.
    for (Vec3& p : mesh.positions)
        p = object_to_world.point(p);
    for (Vec3& n : mesh.normals)
        n = normalize(Transform::normal(*inv, n));
    mesh.flip_normals = reverse_orientation != object_to_world.swaps_handedness();
    ShapeDesc s;
    s.kind = ShapeDesc::Kind::Mesh;
    s.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
    return s;
}

}  // namespace statmc::render
