#include "statmc/render/scene_parser.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include <zlib.h>

#include "statmc/layers/input_path.h"
#include "statmc/render/parameter_list.h"
#include "statmc/render/ply_reader.h"
#include "statmc/render/shapes.h"
#include "statmc/render/texture.h"
#include "statmc/render/tokenizer.h"

namespace statmc::render {

namespace {

namespace fs = std::filesystem;

struct GraphicsState {
    // pbrt-v3 keeps two transformation matrices, for the start and the end of the shutter
    // (ActiveTransform picks which the transform directives change); only the camera's may
    // differ (docs/exr-layers.md: camera animation for sequences).
    Transform ctm, ctm_end;
    bool active_start = true, active_end = true;
    int material = 0;
    std::optional<Rgb> emission;
    bool two_sided = false;
    bool reverse_orientation = false;
};

// The text of a scene file; "" with `why` set (to be prefixed with the path) when it is a
// directory or cannot be opened.
std::string read_scene_text(const std::string& path, std::string& why)
{
    why = layers::input_path_problem(path);
    if (!why.empty())
        return {};
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        why = "cannot open it";
        return {};
    }
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::uint32_t text_crc(std::uint32_t crc, const std::string& text)
{
    return std::uint32_t(
        crc32_z(crc, reinterpret_cast<const Bytef*>(text.data()), text.size()));
}

// Include nests at most this deep (pbrt-v3 sets no limit; a cycle is caught before it).
constexpr int kMaxIncludeDepth = 32;

class Parser {
public:
    Parser(std::vector<Token> tokens, std::string file, std::string directory)
        : tokens_(std::move(tokens)), file_(std::move(file)), dir_(std::move(directory))
    {
        scene_.file = file_;
        scene_.film_where = file_;
        Material matte;
        matte.name = "(default matte)";
        scene_.materials.push_back(matte);
    }

    /// Counts `text` (the main file's) into the scene's source_crc.
    void add_source(const std::string& text) { scene_.source_crc = text_crc(scene_.source_crc, text); }

    SceneDescription run()
    {
        for (;;) {
            if (pos_ < tokens_.size()) {
                directive();
                continue;
            }
            if (includers_.empty())
                break;
            // The included file is done: continue where its Include left off.
            tokens_ = std::move(includers_.back().tokens);
            file_ = std::move(includers_.back().file);
            pos_ = includers_.back().pos;
            includers_.pop_back();
        }
        if (in_world_)
            warn(tokens_.empty() ? 1 : tokens_.back().line, "missing WorldEnd");
        if (!stack_.empty())
            warn(tokens_.empty() ? 1 : tokens_.back().line,
                 "unbalanced AttributeBegin/TransformBegin");
        if (!saw_camera_)
            warn(1, "no Camera directive: using a perspective camera at the origin");
        return std::move(scene_);
    }

private:
    // A file suspended at an Include, resumed when the included file ends.
    struct Includer {
        std::vector<Token> tokens;
        std::string file;
        std::size_t pos;
    };

    std::vector<Token> tokens_;
    std::string file_, dir_;  // the file being read; the main file's directory
    std::size_t pos_ = 0;
    std::vector<Includer> includers_;
    SceneDescription scene_;
    GraphicsState gs_;
    std::vector<std::pair<GraphicsState, bool>> stack_;  // state, is-transform-only
    std::unordered_map<std::string, int> named_materials_;
    NamedTextures textures_;
    std::map<std::string, std::shared_ptr<const TriangleMesh>> ply_cache_;
    bool in_world_ = false;
    bool saw_camera_ = false;

    std::string where(int line) const { return file_ + ":" + std::to_string(line); }
    [[noreturn]] void fail(int line, const std::string& what) const
    {
        throw SceneError(where(line) + ": " + what);
    }
    void warn(int line, const std::string& what)
    {
        scene_.warnings.push_back(where(line) + ": warning: " + what);
    }

    // ---- token helpers ----
    const Token& peek() const { return tokens_[pos_]; }
    bool at_end() const { return pos_ >= tokens_.size(); }
    int last_line() const
    {
        return tokens_.empty() ? 1 : tokens_[std::min(pos_, tokens_.size() - 1)].line;
    }

    std::string expect_string(const std::string& what)
    {
        if (at_end() || peek().kind != Token::Kind::String)
            fail(last_line(), "expected " + what + " (a quoted string)");
        return tokens_[pos_++].text;
    }
    /// n numbers, optionally enclosed in brackets (pbrt accepts both for Transform).
    std::vector<double> numbers(std::size_t n, const std::string& what)
    {
        const bool bracket = !at_end() && peek().kind == Token::Kind::OpenBracket;
        if (bracket)
            ++pos_;
        std::vector<double> v;
        for (std::size_t i = 0; i < n; ++i) {
            if (at_end() || peek().kind != Token::Kind::Number)
                fail(last_line(), what + " needs " + std::to_string(n) + " numbers");
            v.push_back(tokens_[pos_++].number);
        }
        if (bracket) {
            if (at_end() || peek().kind != Token::Kind::CloseBracket)
                fail(last_line(),
                     what + " needs exactly " + std::to_string(n) + " numbers and ']'");
            ++pos_;
        }
        return v;
    }

    ParameterList params(int line) { return ParameterList::parse(tokens_, pos_, file_, line); }
    void warn_all(std::vector<std::string> warnings)
    {
        for (std::string& w : warnings)
            scene_.warnings.push_back(std::move(w));
    }
    std::string resolve(const std::string& name) const
    {
        const fs::path p(name);
        return p.is_absolute() ? name : (fs::path(dir_) / p).string();
    }

    void apply(const Transform& t)
    {
        if (gs_.active_start)
            gs_.ctm = gs_.ctm * t;
        if (gs_.active_end)
            gs_.ctm_end = gs_.ctm_end * t;
    }
    void set(const Transform& t)
    {
        if (gs_.active_start)
            gs_.ctm = t;
        if (gs_.active_end)
            gs_.ctm_end = t;
    }

    // ---- directives ----
    void directive()
    {
        const Token& t = tokens_[pos_];
        if (t.kind != Token::Kind::Identifier)
            fail(t.line, "expected a directive, got '" + t.text + "'");
        ++pos_;
        const std::string& d = t.text;
        const int line = t.line;
        if (d == "LookAt") {
            look_at(line);
        } else if (d == "Transform") {
            set(Transform::from_pbrt(numbers(16, "Transform").data()));
        } else if (d == "ConcatTransform") {
            apply(Transform::from_pbrt(numbers(16, "ConcatTransform").data()));
        } else if (d == "Translate") {
            const auto v = numbers(3, "Translate");
            apply(Transform::translate({float(v[0]), float(v[1]), float(v[2])}));
        } else if (d == "Scale") {
            const auto v = numbers(3, "Scale");
            apply(Transform::scale({float(v[0]), float(v[1]), float(v[2])}));
        } else if (d == "Rotate") {
            const auto v = numbers(4, "Rotate");
            apply(Transform::rotate(v[0], {float(v[1]), float(v[2]), float(v[3])}));
        } else if (d == "Identity") {
            set(Transform::identity());
        } else if (d == "ReverseOrientation") {
            gs_.reverse_orientation = !gs_.reverse_orientation;
        } else if (d == "Camera") {
            camera(line);
        } else if (d == "Film") {
            film(line);
        } else if (d == "Sampler") {
            sampler(line);
        } else if (d == "Integrator") {
            integrator(line);
        } else if (d == "PixelFilter") {
            // Read, not used: the method needs each sample in exactly one pixel (box filter);
            // its parameters are accepted silently.
            expect_string("a filter type");
            params(line);
        } else if (d == "Accelerator" || d == "ColorSpace") {
            expect_string("a type");
            params(line);
            warn(line, d + " ignored");
        } else if (d == "WorldBegin") {
            in_world_ = true;
            gs_.ctm = gs_.ctm_end = Transform::identity();
        } else if (d == "WorldEnd") {
            in_world_ = false;
        } else if (d == "AttributeBegin" || d == "TransformBegin") {
            stack_.push_back({gs_, d == "TransformBegin"});
        } else if (d == "AttributeEnd" || d == "TransformEnd") {
            end_block(d, line);
        } else if (d == "MakeNamedMaterial") {
            make_named_material(line);
        } else if (d == "NamedMaterial") {
            const std::string name = expect_string("a material name");
            const auto it = named_materials_.find(name);
            if (it == named_materials_.end())
                fail(line, "NamedMaterial \"" + name + "\" was not defined");
            gs_.material = it->second;
        } else if (d == "Material") {
            const std::string type = expect_string("a material type");
            auto ps = params(line);
            gs_.material = make_material(type, ps, type);
        } else if (d == "Texture") {
            texture(line);
        } else if (d == "AreaLightSource") {
            area_light(line);
        } else if (d == "LightSource") {
            const std::string type = expect_string("a light type");
            params(line);
            fail(line,
                 "unsupported: LightSource \"" + type + "\" (only area lights are supported)");
        } else if (d == "Shape") {
            shape(line);
        } else if (d == "ActiveTransform") {
            active_transform(line);
        } else if (d == "TransformTimes") {
            const auto v = numbers(2, "TransformTimes");
            if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && v[0] < v[1]))
                fail(line, "TransformTimes: the start time must be below the end time");
            scene_.camera.start_time = v[0];
            scene_.camera.end_time = v[1];
        } else if (d == "Include" || d == "Import") {
            include(d, line);
        } else if (d == "ObjectBegin" || d == "ObjectEnd" || d == "ObjectInstance" ||
                   d == "MakeNamedMedium" || d == "MediumInterface" || d == "CoordinateSystem" ||
                   d == "CoordSysTransform") {
            fail(line, "unsupported: " + d);
        } else {
            warn(line, "unknown directive '" + d + "' ignored");
            // Skip its arguments: everything up to the next identifier.
            while (!at_end() && peek().kind != Token::Kind::Identifier)
                ++pos_;
        }
    }

    /// Include (and Import, which pbrt-v3 does not have and pbrt-v4 reads the same way for
    /// this subset): the named file's directives, in the current graphics state. Relative
    /// names resolve against the main file's directory, as pbrt-v3 does.
    void include(const std::string& d, int line)
    {
        const std::string name = expect_string("the file to " + d);
        const std::string path = resolve(name);
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(path, ec);
        auto same_file = [&](const std::string& other) {
            std::error_code e;
            return fs::weakly_canonical(other, e) == canonical;
        };
        std::string chain;
        bool cycle = same_file(file_);
        for (const Includer& f : includers_) {
            cycle = cycle || same_file(f.file);
            chain += f.file + " -> ";
        }
        if (cycle)
            fail(line, d + " \"" + name + "\" would include itself again (" + chain + file_ +
                           " -> " + path + ")");
        if (int(includers_.size()) >= kMaxIncludeDepth)
            fail(line, d + " nested deeper than " + std::to_string(kMaxIncludeDepth) + " files");
        std::string why;
        const std::string text = read_scene_text(path, why);
        if (!why.empty())
            fail(line, d + " \"" + name + "\": " + path + ": " + why);
        scene_.source_crc = text_crc(scene_.source_crc, text);
        std::vector<Token> tokens = tokenize(text, path);
        includers_.push_back({std::move(tokens_), std::move(file_), pos_});
        tokens_ = std::move(tokens);
        file_ = path;
        pos_ = 0;
    }

    /// ActiveTransform StartTime | EndTime | All: which of the two matrices the transform
    /// directives that follow change.
    void active_transform(int line)
    {
        if (at_end() || peek().kind != Token::Kind::Identifier)
            fail(line, "ActiveTransform: expected StartTime, EndTime or All");
        const std::string which = tokens_[pos_++].text;
        if (which != "StartTime" && which != "EndTime" && which != "All")
            fail(line, "ActiveTransform: expected StartTime, EndTime or All, got '" + which + "'");
        gs_.active_start = which != "EndTime";
        gs_.active_end = which != "StartTime";
    }

    void look_at(int line)
    {
        const auto v = numbers(9, "LookAt");
        const auto la = Transform::look_at({float(v[0]), float(v[1]), float(v[2])},
                                           {float(v[3]), float(v[4]), float(v[5])},
                                           {float(v[6]), float(v[7]), float(v[8])});
        if (!la)
            fail(line, "LookAt: the up vector is parallel to the viewing direction");
        apply(*la);
    }

    /// AttributeEnd or TransformEnd (`d`): restores the state its begin saved.
    void end_block(const std::string& d, int line)
    {
        if (stack_.empty())
            fail(line, d + " without a matching begin");
        if (stack_.back().second != (d == "TransformEnd"))
            fail(line,
                 d + " closes a " + (stack_.back().second ? "TransformBegin" : "AttributeBegin"));
        if (stack_.back().second) {
            gs_.ctm = stack_.back().first.ctm;
            gs_.ctm_end = stack_.back().first.ctm_end;
            gs_.active_start = stack_.back().first.active_start;
            gs_.active_end = stack_.back().first.active_end;
        } else
            gs_ = stack_.back().first;
        stack_.pop_back();
    }

    void film(int line)
    {
        const std::string type = expect_string("a film type");
        auto ps = params(line);
        if (type != "image")
            warn(line, "Film \"" + type + "\" treated as \"image\"");
        scene_.camera.width = ps.get_int("xresolution").value_or(640);
        scene_.camera.height = ps.get_int("yresolution").value_or(480);
        if (scene_.camera.width <= 0 || scene_.camera.height <= 0)
            fail(line, "Film resolution must be positive");
        scene_.film_where = where(line) + ": Film";
        ps.get_string("filename");  // checked, not used: the output name comes from -o
        warn_all(ps.unused_warnings("Film"));
    }

    void sampler(int line)
    {
        expect_string("a sampler type");
        auto ps = params(line);
        scene_.spp = ps.get_int("pixelsamples").value_or(16);
        if (scene_.spp <= 0)
            fail(line, "pixelsamples must be positive");
        warn_all(ps.unused_warnings("Sampler"));
    }

    void integrator(int line)
    {
        const std::string type = expect_string("an integrator type");
        auto ps = params(line);
        if (type != "path")
            warn(line, "Integrator \"" + type + "\" rendered with the path tracer");
        scene_.maxdepth = ps.get_int("maxdepth").value_or(5);
        if (scene_.maxdepth < 0)
            fail(line, "maxdepth must not be negative");
        warn_all(ps.unused_warnings("Integrator"));
    }

    void area_light(int line)
    {
        const std::string type = expect_string("a light type");
        auto ps = params(line);
        if (type != "diffuse")
            fail(line, "unsupported: AreaLightSource \"" + type + "\" (only \"diffuse\")");
        const auto L = ps.get_rgb("L");
        const float scale = ps.get_float("scale").value_or(1.f);
        gs_.emission = (L ? *L : Rgb{1.f}) * scale;
        gs_.two_sided = ps.get_bool("twosided").value_or(false);
        ps.get_int("samples");
        warn_all(ps.unused_warnings("AreaLightSource"));
    }

    void camera(int line)
    {
        const std::string type = expect_string("a camera type");
        auto ps = params(line);
        if (type != "perspective")
            fail(line, "unsupported: Camera \"" + type + "\" (only \"perspective\")");
        saw_camera_ = true;
        scene_.camera.world_to_camera = gs_.ctm;
        scene_.camera.world_to_camera_end = gs_.ctm_end;
        if (scene_.camera.animated() && !camera_motion_is_rigid(scene_.camera))
            fail(line, "Camera: its start and end transforms (ActiveTransform) must differ by a "
                       "rotation and a translation only");
        scene_.camera.fov_degrees = ps.get_float("fov").value_or(90.f);
        if (!(scene_.camera.fov_degrees > 0 && scene_.camera.fov_degrees < 180))
            fail(line, "Camera fov must be in (0, 180) degrees");
        warn_all(ps.ignore({"lensradius", "focaldistance", "frameaspectratio", "screenwindow"},
                           "Camera parameter"));
        warn_all(ps.unused_warnings("Camera"));
    }

    void texture(int line)
    {
        const std::string name = expect_string("a texture name");
        const std::string cls = expect_string("a texture type (\"spectrum\" or \"float\")");
        const std::string type = expect_string("a texture class");
        auto ps = params(line);
        if (type != "imagemap")
            fail(line, "unsupported: Texture \"" + type + "\" (only \"imagemap\")");
        if (cls != "spectrum" && cls != "color" && cls != "rgb")
            fail(line,
                 "unsupported: " + cls + " texture \"" + name + "\" (only spectrum textures)");
        const std::string filename = ps.get_string("filename").value_or("");
        if (filename.empty())
            fail(line, "Texture \"" + name + "\" needs \"string filename\"");
        const bool gamma = ps.get_bool("gamma").value_or(default_texture_gamma(filename));
        const float scale = ps.get_float("scale").value_or(1.f);
        ps.ignore({"trilinear", "maxanisotropy", "wrap",
                   "filter"});  // filtering options: lookups are bilinear
        warn_all(ps.unused_warnings("Texture"));
        const std::string path = resolve(filename);
        try {
            textures_[name] = ImageTexture::load(path, gamma, scale);
        } catch (const std::exception& e) {
            fail(line, e.what());
        }
    }

    void make_named_material(int line)
    {
        const std::string name = expect_string("a material name");
        auto ps = params(line);
        const Parameter* type = ps.find("string", "type");
        if (!type || type->strings.size() != 1)
            fail(line, "MakeNamedMaterial \"" + name + "\" needs \"string type\"");
        named_materials_[name] = make_material(type->strings[0], ps, name);
    }

    /// Reads the material (material.cpp), reports its unknown parameters, and returns its
    /// index in scene_.materials.
    int make_material(const std::string& type, ParameterList& ps, const std::string& name)
    {
        Material m = read_material(type, name, ps, textures_, scene_.warnings);
        ps.find("string", "type");  // MakeNamedMaterial's own parameter: consumed, not unknown
        warn_all(ps.unused_warnings("material \"" + name + "\""));
        scene_.materials.push_back(std::move(m));
        return int(scene_.materials.size()) - 1;
    }

    void shape(int line)
    {
        const std::string type = expect_string("a shape type");
        auto ps = params(line);
        if (!in_world_)
            fail(line, "Shape outside WorldBegin/WorldEnd");
        if (!(gs_.ctm == gs_.ctm_end))
            warn(line, "Shape: animated transforms are not supported; the start transform is "
                       "used");
        ShapeDesc s = read_shape(type, ps, gs_.ctm, gs_.reverse_orientation, ply_loader(line),
                                 scene_.warnings);
        warn_all(ps.unused_warnings("Shape \"" + type + "\""));
        s.material = gs_.material;
        s.emission = gs_.emission;
        s.two_sided = gs_.two_sided;
        s.where = where(line);
        scene_.shapes.push_back(std::move(s));
    }

    /// PLY files resolved against the scene's directory and read once per path; one that
    /// cannot be read is an error at the Shape directive's `line`.
    PlyLoader ply_loader(int line)
    {
        return [this, line](const std::string& filename) {
            const std::string path = resolve(filename);
            auto cached = ply_cache_.find(path);
            if (cached == ply_cache_.end()) {
                try {
                    cached =
                        ply_cache_
                            .emplace(path, std::make_shared<const TriangleMesh>(read_ply(path)))
                            .first;
                } catch (const std::exception& e) {
                    fail(line, e.what());
                }
            }
            return cached->second;
        };
    }
};

}  // namespace

SceneDescription parse_scene_string(const std::string& text, const std::string& file,
                                    const std::string& directory)
{
    Parser parser(tokenize(text, file), file, directory);
    parser.add_source(text);
    return parser.run();
}

SceneDescription parse_scene_file(const std::string& path)
{
    std::string why;
    const std::string text = read_scene_text(path, why);
    if (!why.empty())
        throw SceneError(path + ": " + why);
    const fs::path p(path);
    SceneDescription scene =
        parse_scene_string(text, path, p.has_parent_path() ? p.parent_path().string() : ".");
    // A file that describes nothing would render black and look like success.
    if (scene.shapes.empty())
        throw SceneError(path + ": nothing to render: the scene has no Shape" +
                         (text.find("WorldBegin") == std::string::npos
                              ? std::string(" (and no WorldBegin: is this a pbrt-v3 scene?)")
                              : std::string()));
    return scene;
}

}  // namespace statmc::render
