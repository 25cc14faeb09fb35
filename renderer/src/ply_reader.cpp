#include "ply_reader.h"

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace statmc::render {

namespace {

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Property {
    std::string name;
    std::string type;        ///< scalar type, or the item type of a list
    std::string count_type;  ///< non-empty for lists
};

struct Element {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;
};

int type_size(const std::string& t)
{
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8")
        return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16")
        return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32")
        return 4;
    if (t == "double" || t == "float64")
        return 8;
    return 0;
}

class Reader {
public:
    Reader(std::istream& in, Format format, const std::string& path)
        : in_(in), format_(format), path_(path) {}

    double read(const std::string& type)
    {
        if (format_ == Format::Ascii) {
            double v;
            if (!(in_ >> v))
                fail("truncated or malformed ASCII data");
            return v;
        }
        unsigned char b[8];
        const int n = type_size(type);
        if (!in_.read(reinterpret_cast<char*>(b), n))
            fail("truncated binary data");
        const bool little = format_ == Format::BinaryLittle;
        unsigned char le[8];
        for (int i = 0; i < n; ++i)
            le[i] = little ? b[i] : b[n - 1 - i];
        // The host is little-endian (x86-64, the only target Embree runs on here).
        if (type == "char" || type == "int8") { std::int8_t v; std::memcpy(&v, le, 1); return v; }
        if (type == "uchar" || type == "uint8") { return le[0]; }
        if (type == "short" || type == "int16") { std::int16_t v; std::memcpy(&v, le, 2); return v; }
        if (type == "ushort" || type == "uint16") { std::uint16_t v; std::memcpy(&v, le, 2); return v; }
        if (type == "int" || type == "int32") { std::int32_t v; std::memcpy(&v, le, 4); return v; }
        if (type == "uint" || type == "uint32") { std::uint32_t v; std::memcpy(&v, le, 4); return v; }
        if (type == "float" || type == "float32") { float v; std::memcpy(&v, le, 4); return v; }
        double v;
        std::memcpy(&v, le, 8);
        return v;
    }

    [[noreturn]] void fail(const std::string& why) const
    {
        throw std::runtime_error("'" + path_ + "': " + why);
    }

private:
    std::istream& in_;
    Format format_;
    const std::string& path_;
};

}  // namespace

TriangleMesh read_ply(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error("cannot open mesh '" + path + "'");
    auto fail = [&](const std::string& why) { throw std::runtime_error("'" + path + "': " + why); };

    std::string line;
    if (!std::getline(in, line) || line.rfind("ply", 0) != 0)
        fail("not a PLY file");
    Format format = Format::Ascii;
    std::vector<Element> elements;
    bool header_done = false;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        std::istringstream ls(line);
        std::string word;
        ls >> word;
        if (word == "format") {
            std::string f;
            ls >> f;
            if (f == "ascii") format = Format::Ascii;
            else if (f == "binary_little_endian") format = Format::BinaryLittle;
            else if (f == "binary_big_endian") format = Format::BinaryBig;
            else fail("unknown format '" + f + "'");
        } else if (word == "element") {
            Element e;
            ls >> e.name >> e.count;
            elements.push_back(e);
        } else if (word == "property") {
            if (elements.empty())
                fail("property before any element");
            Property p;
            std::string t;
            ls >> t;
            if (t == "list") {
                ls >> p.count_type >> p.type >> p.name;
                if (!type_size(p.count_type) || !type_size(p.type))
                    fail("unknown list type in '" + line + "'");
            } else {
                p.type = t;
                ls >> p.name;
                if (!type_size(p.type))
                    fail("unknown property type '" + t + "'");
            }
            elements.back().properties.push_back(p);
        } else if (word == "end_header") {
            header_done = true;
            break;
        }
    }
    if (!header_done)
        fail("no end_header");

    TriangleMesh mesh;
    Reader reader(in, format, path);
    for (const Element& e : elements) {
        if (e.name == "vertex") {
            int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1;
            for (int i = 0; i < int(e.properties.size()); ++i) {
                const std::string& n = e.properties[i].name;
                if (n == "x") ix = i;
                else if (n == "y") iy = i;
                else if (n == "z") iz = i;
                else if (n == "nx") inx = i;
                else if (n == "ny") iny = i;
                else if (n == "nz") inz = i;
                else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") iu = i;
                else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") iv = i;
            }
            if (ix < 0 || iy < 0 || iz < 0)
                fail("vertices lack x, y or z");
            const bool has_n = inx >= 0 && iny >= 0 && inz >= 0, has_uv = iu >= 0 && iv >= 0;
            std::vector<double> values(e.properties.size());
            for (std::size_t k = 0; k < e.count; ++k) {
                for (std::size_t i = 0; i < e.properties.size(); ++i) {
                    const Property& p = e.properties[i];
                    if (!p.count_type.empty()) {
                        const auto n = std::size_t(reader.read(p.count_type));
                        for (std::size_t j = 0; j < n; ++j)
                            reader.read(p.type);
                        values[i] = 0;
                    } else {
                        values[i] = reader.read(p.type);
                    }
                }
                mesh.positions.push_back({float(values[ix]), float(values[iy]), float(values[iz])});
                if (has_n)
                    mesh.normals.push_back({float(values[inx]), float(values[iny]), float(values[inz])});
                if (has_uv) {
                    mesh.uvs.push_back(float(values[iu]));
                    mesh.uvs.push_back(float(values[iv]));
                }
            }
        } else {
            const bool is_face = e.name == "face";
            for (std::size_t k = 0; k < e.count; ++k) {
                for (const Property& p : e.properties) {
                    if (p.count_type.empty()) {
                        reader.read(p.type);
                        continue;
                    }
                    const auto n = std::size_t(reader.read(p.count_type));
                    std::vector<std::uint32_t> idx(n);
                    for (std::size_t j = 0; j < n; ++j)
                        idx[j] = std::uint32_t(reader.read(p.type));
                    if (!is_face || (p.name != "vertex_indices" && p.name != "vertex_index"))
                        continue;
                    if (n < 3)
                        fail("a face with fewer than 3 vertices");
                    for (std::size_t j = 1; j + 1 < n; ++j) {  // fan: triangles and quads
                        mesh.indices.push_back(idx[0]);
                        mesh.indices.push_back(idx[j]);
                        mesh.indices.push_back(idx[j + 1]);
                    }
                }
            }
        }
    }
    for (std::uint32_t i : mesh.indices)
        if (i >= mesh.positions.size())
            fail("face index " + std::to_string(i) + " out of range");
    if (mesh.indices.empty())
        fail("no faces");
    return mesh;
}

}  // namespace statmc::render
