#include "statmc/render/ply_reader.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "statmc/layers/input_path.h"
#include "statmc/render/parameter_list.h"

namespace statmc::render {

namespace {

enum class Format { Ascii, BinaryLittle, BinaryBig };

enum class Type { Invalid, Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct Property {
    std::string name;
    Type type = Type::Invalid;        ///< scalar type, or the item type of a list
    Type count_type = Type::Invalid;  ///< set for lists
    bool is_list() const { return count_type != Type::Invalid; }
};

struct Element {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;
};

Type parse_type(const std::string& t)
{
    if (t == "char" || t == "int8")
        return Type::Int8;
    if (t == "uchar" || t == "uint8")
        return Type::UInt8;
    if (t == "short" || t == "int16")
        return Type::Int16;
    if (t == "ushort" || t == "uint16")
        return Type::UInt16;
    if (t == "int" || t == "int32")
        return Type::Int32;
    if (t == "uint" || t == "uint32")
        return Type::UInt32;
    if (t == "float" || t == "float32")
        return Type::Float32;
    if (t == "double" || t == "float64")
        return Type::Float64;
    return Type::Invalid;
}

int type_size(Type t)
{
    switch (t) {
    case Type::Int8:
    case Type::UInt8:
        return 1;
    case Type::Int16:
    case Type::UInt16:
        return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32:
        return 4;
    case Type::Float64:
        return 8;
    case Type::Invalid:
        break;
    }
    return 0;
}

class Reader {
public:
    Reader(std::istream& in, Format format, const std::string& path, std::uintmax_t file_size)
        : in_(in), format_(format), path_(path), file_size_(file_size)
    {
        // Binary bodies are read in one go and decoded from memory: per-value stream
        // reads dominated loading Veach Ajar's 17 meshes.
        if (format_ != Format::Ascii)
            data_.assign(std::istreambuf_iterator<char>(in_), std::istreambuf_iterator<char>());
    }

    double read(Type type)
    {
        if (format_ == Format::Ascii) {
            double v;
            if (!(in_ >> v))
                fail("truncated or malformed ASCII data");
            return v;
        }
        const int n = type_size(type);
        if (pos_ + std::size_t(n) > data_.size())
            fail("truncated binary data");
        const auto* b = reinterpret_cast<const unsigned char*>(data_.data() + pos_);
        pos_ += std::size_t(n);
        const bool little = format_ == Format::BinaryLittle;
        unsigned char le[8];
        for (int i = 0; i < n; ++i)
            le[i] = little ? b[i] : b[n - 1 - i];
        // The host is little-endian (x86-64, the only target Embree runs on here).
        switch (type) {
        case Type::Int8: {
            std::int8_t v;
            std::memcpy(&v, le, 1);
            return v;
        }
        case Type::UInt8:
            return le[0];
        case Type::Int16: {
            std::int16_t v;
            std::memcpy(&v, le, 2);
            return v;
        }
        case Type::UInt16: {
            std::uint16_t v;
            std::memcpy(&v, le, 2);
            return v;
        }
        case Type::Int32: {
            std::int32_t v;
            std::memcpy(&v, le, 4);
            return v;
        }
        case Type::UInt32: {
            std::uint32_t v;
            std::memcpy(&v, le, 4);
            return v;
        }
        case Type::Float32: {
            float v;
            std::memcpy(&v, le, 4);
            return v;
        }
        case Type::Float64: {
            double v;
            std::memcpy(&v, le, 8);
            return v;
        }
        case Type::Invalid:
            break;
        }
        fail("invalid property type");
    }

    /// Bytes not yet read: every value takes at least one, so no count may exceed it.
    std::size_t remaining()
    {
        if (format_ != Format::Ascii)
            return data_.size() - pos_;
        const std::streamoff at = in_.tellg();
        return at < 0 || std::uintmax_t(at) > file_size_ ? 0
                                                          : std::size_t(file_size_ - std::uintmax_t(at));
    }

    /// A list's item count: a whole number the rest of the file can hold (for ASCII, the
    /// whole file: asking the stream for its position per list would cost a system call).
    std::size_t read_count(Type type)
    {
        const double v = read(type);
        const double bound = double(format_ == Format::Ascii ? file_size_ : remaining());
        if (!(v >= 0 && v == std::floor(v) && v <= bound))
            fail("a list of " + number_text(v) + " items, more than the rest of the file holds");
        return std::size_t(v);
    }

    /// A vertex index: a whole number in [0, 2^32).
    std::uint32_t read_index(Type type)
    {
        const double v = read(type);
        if (!(v >= 0 && v == std::floor(v) && v < 4294967296.0))
            fail("face index " + number_text(v) + " out of range");
        return std::uint32_t(v);
    }

    [[noreturn]] void fail(const std::string& why) const
    {
        throw std::runtime_error("'" + path_ + "': " + why);
    }

private:
    std::istream& in_;
    Format format_;
    const std::string& path_;
    std::uintmax_t file_size_;
    std::vector<char> data_;
    std::size_t pos_ = 0;
};

}  // namespace

TriangleMesh read_ply(const std::string& path)
{
    if (const std::string problem = layers::input_path_problem(path); !problem.empty())
        throw std::runtime_error("mesh '" + path + "': " + problem);
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
            if (f == "ascii")
                format = Format::Ascii;
            else if (f == "binary_little_endian")
                format = Format::BinaryLittle;
            else if (f == "binary_big_endian")
                format = Format::BinaryBig;
            else
                fail("unknown format '" + f + "'");
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
                std::string count_type, item_type;
                ls >> count_type >> item_type >> p.name;
                p.count_type = parse_type(count_type);
                p.type = parse_type(item_type);
                if (p.count_type == Type::Invalid || p.type == Type::Invalid)
                    fail("unknown list type in '" + line + "'");
            } else {
                p.type = parse_type(t);
                ls >> p.name;
                if (p.type == Type::Invalid)
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
    std::error_code ec;
    Reader reader(in, format, path, std::filesystem::file_size(path, ec));
    for (const Element& e : elements) {
        if (e.properties.empty())
            continue;  // nothing to read, however many it declares
        if (e.count > reader.remaining())
            fail("element '" + e.name + "' declares " + std::to_string(e.count) +
                 " entries, more than the rest of the file holds");
        if (e.name == "vertex") {
            int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1;
            for (int i = 0; i < int(e.properties.size()); ++i) {
                const std::string& n = e.properties[i].name;
                if (n == "x")
                    ix = i;
                else if (n == "y")
                    iy = i;
                else if (n == "z")
                    iz = i;
                else if (n == "nx")
                    inx = i;
                else if (n == "ny")
                    iny = i;
                else if (n == "nz")
                    inz = i;
                else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")
                    iu = i;
                else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")
                    iv = i;
            }
            if (ix < 0 || iy < 0 || iz < 0)
                fail("vertices lack x, y or z");
            const bool has_n = inx >= 0 && iny >= 0 && inz >= 0, has_uv = iu >= 0 && iv >= 0;
            std::vector<double> values(e.properties.size());
            for (std::size_t k = 0; k < e.count; ++k) {
                for (std::size_t i = 0; i < e.properties.size(); ++i) {
                    const Property& p = e.properties[i];
                    if (p.is_list()) {
                        const std::size_t n = reader.read_count(p.count_type);
                        for (std::size_t j = 0; j < n; ++j)
                            reader.read(p.type);
                        values[i] = 0;
                    } else {
                        values[i] = reader.read(p.type);
                    }
                }
                mesh.positions.push_back({float(values[ix]), float(values[iy]), float(values[iz])});
                if (has_n)
                    mesh.normals.push_back(
                        {float(values[inx]), float(values[iny]), float(values[inz])});
                if (has_uv) {
                    mesh.uvs.push_back(float(values[iu]));
                    mesh.uvs.push_back(float(values[iv]));
                }
            }
        } else {
            const bool is_face = e.name == "face";
            std::vector<std::uint32_t> idx;
            for (std::size_t k = 0; k < e.count; ++k) {
                for (const Property& p : e.properties) {
                    if (!p.is_list()) {
                        reader.read(p.type);
                        continue;
                    }
                    const std::size_t n = reader.read_count(p.count_type);
                    if (!is_face || (p.name != "vertex_indices" && p.name != "vertex_index")) {
                        for (std::size_t j = 0; j < n; ++j)  // texcoords and the like: skipped
                            reader.read(p.type);
                        continue;
                    }
                    idx.resize(n);
                    for (std::size_t j = 0; j < n; ++j)
                        idx[j] = reader.read_index(p.type);
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
