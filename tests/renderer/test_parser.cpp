// The pbrt-v3 reader: each directive, and messages that name file and line.
#include <gtest/gtest.h>

#include <filesystem>

#include <OpenImageIO/imagebuf.h>

#include "renderer_test_support.h"
#include "statmc/render/scene_parser.h"
#include "statmc/render/texture.h"
#include "statmc/render/tokenizer.h"

using namespace statmc::render;
using statmc::render::test::ScratchDir;

namespace {

SceneDescription parse(const std::string& text, const std::string& dir = ".")
{
    return parse_scene_string(text, "t.pbrt", dir);
}

std::string error_of(const std::string& text, const std::string& dir = ".")
{
    try {
        parse(text, dir);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string file_error_of(const std::string& path)
{
    try {
        parse_scene_file(path);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

void expect_near(Vec3 a, Vec3 b, float tol = 1e-5f)
{
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

const char* kTriangle =
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2] \"point P\" [0 0 0 1 0 0 0 1 0]\n";

}  // namespace

TEST(Parser, RenderSettingsFromFilmSamplerIntegratorCamera)
{
    const auto s = parse("LookAt 0 0 -5  0 0 0  0 1 0\n"
                         "Camera \"perspective\" \"float fov\" [ 30 ]\n"
                         "Film \"image\" \"integer xresolution\" [ 200 ] \"integer yresolution\" "
                         "100 \"string filename\" \"x.exr\"\n"
                         "Sampler \"sobol\" \"integer pixelsamples\" 32\n"
                         "Integrator \"path\" \"integer maxdepth\" [ 7 ]\n"
                         "PixelFilter \"triangle\" \"float xwidth\" 1\n"
                         "WorldBegin\nWorldEnd\n");
    EXPECT_EQ(s.camera.width, 200);
    EXPECT_EQ(s.camera.height, 100);
    EXPECT_FLOAT_EQ(s.camera.fov_degrees, 30.f);
    EXPECT_EQ(s.spp, 32);
    EXPECT_EQ(s.maxdepth, 7);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    // LookAt from (0,0,-5) towards the origin: the world origin is 5 units ahead.
    expect_near(s.camera.world_to_camera.point({0, 0, 0}), {0, 0, 5});
}

TEST(Parser, TransformDirectivesComposeLikePbrt)
{
    const auto s = parse(
        "WorldBegin\n"
        "Translate 1 2 3\n"
        "Shape \"sphere\" \"float radius\" 0.5\n"
        "AttributeBegin\n Scale 2 2 2\n Shape \"sphere\"\nAttributeEnd\n"
        "TransformBegin\n Rotate 90 0 0 1\n Translate 1 0 0\n Shape \"sphere\"\nTransformEnd\n"
        "ConcatTransform [1 0 0 0  0 1 0 0  0 0 1 0  10 0 0 1]\n"
        "Shape \"sphere\"\n"
        "Transform [1 0 0 0  0 1 0 0  0 0 1 0  0 0 -4 1]\n"
        "Shape \"sphere\"\n"
        "WorldEnd\n");
    ASSERT_EQ(s.shapes.size(), 5u);
    expect_near(s.shapes[0].center, {1, 2, 3});
    EXPECT_FLOAT_EQ(s.shapes[0].radius, 0.5f);
    expect_near(s.shapes[1].center, {1, 2, 3});
    EXPECT_FLOAT_EQ(s.shapes[1].radius, 2.f);
    expect_near(s.shapes[2].center, {1, 3, 3});   // rotated +x onto +y, then translated
    expect_near(s.shapes[3].center, {11, 2, 3});  // the transform block was undone
    expect_near(s.shapes[4].center, {0, 0, -4});  // Transform replaces the CTM
}

TEST(Parser, TriangleMeshIsTransformedToWorldSpace)
{
    const auto s =
        parse("WorldBegin\nTranslate 0 0 5\n"
              "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] \"point P\" [0 0 0 1 0 0 1 "
              "1 0 0 1 0]"
              " \"normal N\" [0 0 1 0 0 1 0 0 1 0 0 1] \"float uv\" [0 0 1 0 1 1 0 1]\nWorldEnd\n");
    ASSERT_EQ(s.shapes.size(), 1u);
    const TriangleMesh& m = *s.shapes[0].mesh;
    ASSERT_EQ(m.positions.size(), 4u);
    expect_near(m.positions[2], {1, 1, 5});
    EXPECT_EQ(m.indices.size(), 6u);
    EXPECT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.uvs.size(), 8u);
}

TEST(Parser, MaterialsNamedAndAnonymous)
{
    const auto s = parse(
        "WorldBegin\n"
        "MakeNamedMaterial \"red\" \"string type\" \"matte\" \"rgb Kd\" [0.5 0.1 0.1]\n"
        "MakeNamedMaterial \"m\" \"string type\" \"metal\" \"rgb eta\" [1 2 3] \"rgb k\" [4 5 6]"
        " \"bool remaproughness\" \"false\" \"float uroughness\" 0.1 \"float vroughness\" 0.2\n"
        "NamedMaterial \"red\"\n" +
        std::string(kTriangle) + "NamedMaterial \"m\"\n" + kTriangle +
        "Material \"glass\" \"float index\" 1.33\n" + kTriangle + "Material \"mirror\"\n" +
        kTriangle + "Material \"metal\" \"float roughness\" 0.5\n" + kTriangle + "WorldEnd\n");
    ASSERT_EQ(s.shapes.size(), 5u);
    const Material& red = s.materials[std::size_t(s.shapes[0].material)];
    EXPECT_EQ(red.type, Material::Type::Matte);
    EXPECT_FLOAT_EQ(red.kd.g, 0.1f);
    const Material& m = s.materials[std::size_t(s.shapes[1].material)];
    EXPECT_EQ(m.type, Material::Type::Metal);
    EXPECT_FLOAT_EQ(m.alpha_u, 0.1f);
    EXPECT_FLOAT_EQ(m.alpha_v, 0.2f);
    EXPECT_FLOAT_EQ(m.k.b, 6.f);
    const Material& g = s.materials[std::size_t(s.shapes[2].material)];
    EXPECT_EQ(g.type, Material::Type::Glass);
    EXPECT_FLOAT_EQ(g.ior, 1.33f);
    const Material& mi = s.materials[std::size_t(s.shapes[3].material)];
    EXPECT_EQ(mi.type, Material::Type::Mirror);
    EXPECT_FLOAT_EQ(mi.kr.r, 0.9f);  // pbrt-v3's default Kr
    const Material& rough = s.materials[std::size_t(s.shapes[4].material)];
    EXPECT_FLOAT_EQ(rough.alpha_u, roughness_to_alpha(0.5f));  // remapped by default
}

TEST(Parser, AreaLightAppliesInsideItsAttributeBlockOnly)
{
    const auto s = parse(std::string("WorldBegin\nAttributeBegin\n"
                                     "AreaLightSource \"diffuse\" \"rgb L\" [1 2 3]\n") +
                         kTriangle + "AttributeEnd\n" + kTriangle + "WorldEnd\n");
    ASSERT_EQ(s.shapes.size(), 2u);
    ASSERT_TRUE(s.shapes[0].emission);
    EXPECT_FLOAT_EQ(s.shapes[0].emission->b, 3.f);
    EXPECT_FALSE(s.shapes[1].emission);
}

TEST(Parser, ImageMapTextureIsReadAndFlippedInV)
{
    ScratchDir dir("texture");
    // 1x2 image: top row red, bottom row blue. pbrt puts v = 0 at the bottom.
    OIIO::ImageBuf img(OIIO::ImageSpec(1, 2, 3, OIIO::TypeDesc::FLOAT));
    const float red[3] = {1, 0, 0}, blue[3] = {0, 0, 1};
    img.setpixel(0, 0, red);
    img.setpixel(0, 1, blue);
    ASSERT_TRUE(img.write(dir.file("tex.exr")));
    const auto s = parse(
        "WorldBegin\nTexture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"tex.exr\"\n"
        "Material \"matte\" \"texture Kd\" \"t\"\n" +
            std::string(kTriangle) + "WorldEnd\n",
        dir.file(""));
    const Material& m = s.materials[std::size_t(s.shapes[0].material)];
    ASSERT_TRUE(m.kd_texture);
    // Row centres (lookups are bilinear with repeat wrapping): v = 0.25 is the bottom row.
    const Rgb bottom = m.kd_texture->lookup(0.5f, 0.25f), top = m.kd_texture->lookup(0.5f, 0.75f);
    EXPECT_GT(bottom.b, 0.9f);
    EXPECT_GT(top.r, 0.9f);
}

TEST(Parser, PlyMeshAsciiWithQuadsAndTransform)
{
    ScratchDir dir("ply");
    dir.write("q.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float "
                       "y\nproperty float z\n"
                       "property float u\nproperty float v\nelement face 1\nproperty list uchar "
                       "int vertex_indices\n"
                       "end_header\n0 0 0 0 0\n1 0 0 1 0\n1 1 0 1 1\n0 1 0 0 1\n4 0 1 2 3\n");
    const auto s = parse(
        "WorldBegin\nScale 2 2 2\nShape \"plymesh\" \"string filename\" \"q.ply\"\nWorldEnd\n",
        dir.file(""));
    ASSERT_EQ(s.shapes.size(), 1u);
    const TriangleMesh& m = *s.shapes[0].mesh;
    EXPECT_EQ(m.indices.size(), 6u);  // the quad split in two
    expect_near(m.positions[2], {2, 2, 0});
    EXPECT_EQ(m.uvs.size(), 8u);
}

TEST(Parser, UnknownDirectiveAndParameterWarnWithFileAndLine)
{
    const auto s = parse("WorldBegin\nFrobnicate \"x\" [1 2]\n"
                         "Shape \"sphere\" \"float radius\" 1 \"float wobble\" 3\nWorldEnd\n");
    // (The scene also has no Camera, which is a third warning.)
    ASSERT_EQ(s.warnings.size(), 3u);
    EXPECT_NE(s.warnings[0].find("t.pbrt:2: warning: unknown directive 'Frobnicate'"),
              std::string::npos)
        << s.warnings[0];
    EXPECT_NE(s.warnings[1].find("t.pbrt:3: warning: unknown parameter \"float wobble\""),
              std::string::npos)
        << s.warnings[1];
    EXPECT_EQ(s.shapes.size(), 1u);  // parsing went on
}

TEST(Parser, MalformedInputNamesFileAndLine)
{
    EXPECT_NE(
        error_of("WorldBegin\n\nShape \"sphere\" \"float radius\" \"oops\n").find("t.pbrt:3:"),
        std::string::npos);
    EXPECT_NE(error_of("Transform [1 2 3]\n").find("t.pbrt:1: Transform needs"), std::string::npos)
        << error_of("Transform [1 2 3]\n");
    EXPECT_NE(error_of("WorldBegin\nNamedMaterial \"nope\"\n")
                  .find("t.pbrt:2: NamedMaterial \"nope\" was not defined"),
              std::string::npos);
    EXPECT_NE(error_of("WorldBegin\nAttributeEnd\n").find("t.pbrt:2:"), std::string::npos);
    EXPECT_NE(error_of("WorldBegin\nShape \"trianglemesh\" \"integer indices\" [0 1 7] "
                       "\"point P\" [0 0 0 1 0 0 0 1 0]\n")
                  .find("t.pbrt:2: index 7 out of range"),
              std::string::npos);
    EXPECT_NE(error_of("Film \"image\" \"integer xresolution\" [ 10 \n").find("t.pbrt:1:"),
              std::string::npos);
    EXPECT_NE(error_of("Camera \"perspective\" \"float fov\" [ 30 ] @\n")
                  .find("t.pbrt:1: unexpected character"),
              std::string::npos);
}

TEST(Parser, MissingFilesAndUnsupportedFeaturesAreClearErrors)
{
    const std::string ply =
        error_of("WorldBegin\n\nShape \"plymesh\" \"string filename\" \"missing.ply\"\n");
    EXPECT_NE(ply.find("t.pbrt:3:"), std::string::npos) << ply;
    EXPECT_NE(ply.find("missing.ply"), std::string::npos) << ply;
    const std::string tex = error_of(
        "WorldBegin\nTexture \"t\" \"spectrum\" \"imagemap\" \"string filename\" \"no.tga\"\n");
    EXPECT_NE(tex.find("t.pbrt:2:"), std::string::npos) << tex;
    EXPECT_NE(tex.find("no.tga"), std::string::npos) << tex;
    EXPECT_NE(
        error_of("WorldBegin\nShape \"cone\"\n").find("t.pbrt:2: unsupported: Shape \"cone\""),
        std::string::npos);
    EXPECT_NE(error_of("WorldBegin\nMaterial \"plastic\"\n")
                  .find("t.pbrt:2: unsupported: material \"plastic\""),
              std::string::npos);
    EXPECT_NE(error_of("LightSource \"point\"\n").find("t.pbrt:1: unsupported: LightSource"),
              std::string::npos);
    EXPECT_NE(error_of("Camera \"orthographic\"\n").find("t.pbrt:1: unsupported: Camera"),
              std::string::npos);
    EXPECT_NE(error_of("WorldBegin\nAreaLightSource \"diffuse\" \"spectrum L\" [400 1 700 1]\n")
                  .find("t.pbrt:2: unsupported"),
              std::string::npos);
}

TEST(Parser, NonFiniteNumbersAreNamed)
{
    const std::string nan = error_of("Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 nan 1]\n");
    EXPECT_EQ(nan, "t.pbrt:1: 'nan' is not a finite number");
    EXPECT_EQ(error_of("Translate 0 -Inf 0\n"), "t.pbrt:1: number '-Inf' is not finite");
    EXPECT_EQ(error_of("Scale 1 1e999 1\n"), "t.pbrt:1: number '1e999' is not finite");
}

TEST(Parser, IntegersMustBeWholeAndFitAnInt)
{
    EXPECT_EQ(error_of("Film \"image\" \"integer xresolution\" [ 5e9 ]\n"),
              "t.pbrt:1: \"integer xresolution\" needs a whole number that fits an int, got 5e+09");
    EXPECT_EQ(error_of("Sampler \"random\" \"integer pixelsamples\" 2.5\n"),
              "t.pbrt:1: \"integer pixelsamples\" needs a whole number that fits an int, got 2.5");
    EXPECT_NE(error_of("WorldBegin\nShape \"trianglemesh\" \"integer indices\" [0 1 1.5] "
                       "\"point P\" [0 0 0 1 0 0 0 1 0]\n")
                  .find("t.pbrt:2: index 1.5 out of range"),
              std::string::npos);
}

TEST(Parser, DeepNestingIsNoProblem)
{
    // The graphics-state stack is a vector, not the call stack.
    std::string text = "WorldBegin\n";
    for (int i = 0; i < 100000; ++i)
        text += "AttributeBegin\n";
    text += kTriangle;
    for (int i = 0; i < 100000; ++i)
        text += "AttributeEnd\n";
    EXPECT_EQ(parse(text).shapes.size(), 1u);
}

TEST(Parser, IncludeReadsAnotherFileInTheSameGraphicsState)
{
    ScratchDir dir("include");
    std::filesystem::create_directories(dir.file("parts"));
    dir.write("parts/lights.pbrt",
              "AreaLightSource \"diffuse\" \"rgb L\" [2 2 2]\nInclude \"parts/mesh.pbrt\"\n");
    dir.write("parts/mesh.pbrt", kTriangle);
    const SceneDescription s =
        parse_scene_file(dir.write("main.pbrt", "WorldBegin\nAttributeBegin\nTranslate 0 0 5\n"
                                                "Include \"parts/lights.pbrt\"\nAttributeEnd\n" +
                                                    std::string(kTriangle) + "WorldEnd\n"));
    ASSERT_EQ(s.shapes.size(), 2u);
    // The included triangle carries the includer's light and transform; the one after the
    // block neither.
    ASSERT_TRUE(s.shapes[0].emission.has_value());
    EXPECT_FLOAT_EQ(s.shapes[0].emission->r, 2.f);
    EXPECT_FLOAT_EQ(s.shapes[0].mesh->positions[0].z, 5.f);
    EXPECT_FALSE(s.shapes[1].emission.has_value());
    EXPECT_NE(s.shapes[0].where.find("mesh.pbrt:1"), std::string::npos) << s.shapes[0].where;
}

TEST(Parser, IncludeCyclesMissingFilesAndDepthAreErrors)
{
    ScratchDir dir("include");
    dir.write("a.pbrt", "Include \"b.pbrt\"\n");
    dir.write("b.pbrt", "\nInclude \"a.pbrt\"\n");
    const std::string cycle = file_error_of(dir.file("a.pbrt"));
    EXPECT_NE(cycle.find("b.pbrt:2: Include \"a.pbrt\" would include itself again"),
              std::string::npos)
        << cycle;
    const std::string missing =
        file_error_of(dir.write("m.pbrt", "WorldBegin\nInclude \"nothere.pbrt\"\n"));
    EXPECT_NE(missing.find("m.pbrt:2: Include \"nothere.pbrt\": "), std::string::npos) << missing;
    EXPECT_NE(missing.find("nothere.pbrt: no such file"), std::string::npos) << missing;
    // A chain of 40 distinct files: deeper than the limit of 32.
    for (int i = 0; i < 40; ++i)
        dir.write("d" + std::to_string(i) + ".pbrt",
                  "Include \"d" + std::to_string(i + 1) + ".pbrt\"\n");
    const std::string deep = file_error_of(dir.file("d0.pbrt"));
    EXPECT_NE(deep.find("nested deeper than 32 files"), std::string::npos) << deep;
}

TEST(Parser, AFileWithNothingToRenderIsAnError)
{
    ScratchDir dir("empty");
    const std::string empty = dir.write("empty.pbrt", "");
    EXPECT_EQ(file_error_of(empty), empty + ": nothing to render: the scene has no Shape (and no "
                                            "WorldBegin: is this a pbrt-v3 scene?)");
    const std::string no_shape = dir.write("lights.pbrt", "WorldBegin\nWorldEnd\n");
    EXPECT_EQ(file_error_of(no_shape), no_shape + ": nothing to render: the scene has no Shape");
    std::filesystem::create_directories(dir.file("folder"));
    EXPECT_EQ(file_error_of(dir.file("folder")),
              dir.file("folder") + ": is a directory, not a file");
}

TEST(Parser, EndlessFilesAreRefusedBeforeTheyAreRead)
{
    // A device would be read for ever (and held in memory): scene, Include and mesh alike.
    EXPECT_EQ(file_error_of("/dev/zero"),
              "/dev/zero: is not a regular file (a device, pipe or socket)");
    const std::string include = error_of("Include \"/dev/zero\"\n");
    EXPECT_NE(include.find("Include \"/dev/zero\": /dev/zero: is not a regular file"),
              std::string::npos)
        << include;
    const std::string mesh =
        error_of("WorldBegin\nShape \"plymesh\" \"string filename\" \"/dev/urandom\"\n");
    EXPECT_NE(mesh.find("mesh '/dev/urandom': is not a regular file"), std::string::npos) << mesh;
}

TEST(Parser, SharedScenesParse)
{
    const std::string shared = statmc::render::test::shared_dir();
    if (shared.empty())
        GTEST_SKIP() << "../shared/scenes not present";
    for (const char* name : {"cornell-box", "veach-mis", "veach-ajar"}) {
        const auto s = parse_scene_file(shared + "/scenes/" + name + "/scene.pbrt");
        EXPECT_FALSE(s.shapes.empty()) << name;
        EXPECT_TRUE(s.warnings.empty()) << name << ": " << s.warnings.front();
    }
}

TEST(Parser, PlyMeshBinaryBothEndiannesses)
{
    // One triangle with double coordinates, normals and an int index list (uchar count).
    auto put = [](std::string& out, const void* p, std::size_t n, bool big) {
        const auto* b = static_cast<const char*>(p);
        for (std::size_t i = 0; i < n; ++i)
            out += big ? b[n - 1 - i] : b[i];
    };
    for (const bool big : {false, true}) {
        std::string ply =
            std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
            " 1.0\ncomment test\nelement vertex 3\nproperty double x\nproperty double y\n"
            "property double z\nproperty float nx\nproperty float ny\nproperty float nz\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
        const double pos[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}};
        for (const auto& v : pos) {
            for (double c : v)
                put(ply, &c, sizeof c, big);
            const float n[3] = {0, 0, 1};
            for (float c : n)
                put(ply, &c, sizeof c, big);
        }
        ply += char(3);
        for (std::int32_t i : {0, 1, 2})
            put(ply, &i, sizeof i, big);
        ScratchDir dir("plybin");
        dir.write("t.ply", ply);
        const auto s =
            parse("WorldBegin\nShape \"plymesh\" \"string filename\" \"t.ply\"\nWorldEnd\n",
                  dir.file(""));
        ASSERT_EQ(s.shapes.size(), 1u);
        const TriangleMesh& m = *s.shapes[0].mesh;
        ASSERT_EQ(m.positions.size(), 3u);
        expect_near(m.positions[2], {0, 2, 0});
        ASSERT_EQ(m.normals.size(), 3u);
        expect_near(m.normals[1], {0, 0, 1});
        EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2}));
    }
}

TEST(Parser, PlyCountsAndIndicesMustFitTheFile)
{
    ScratchDir dir("plycounts");
    const std::string header = "ply\nformat binary_little_endian 1.0\n";
    const std::string vertex = "property float x\nproperty float y\nproperty float z\n";
    const std::string body(3 * 12, '\0');  // three vertices at the origin
    auto ply_error = [&](const std::string& ply) {
        dir.write("t.ply", ply);
        return error_of("WorldBegin\nShape \"plymesh\" \"string filename\" \"t.ply\"\n",
                        dir.file(""));
    };
    auto face = [](std::int32_t count, std::int32_t index) {
        std::string f(reinterpret_cast<const char*>(&count), 4);
        for (int k = 0; k < 3; ++k)
            f.append(reinterpret_cast<const char*>(&index), 4);
        return f;
    };
    const std::string faces =
        "element face 1\nproperty list int int vertex_indices\nend_header\n";
    // A billion vertices declared, 36 bytes given: refused before anything is allocated.
    std::string e = ply_error(header + "element vertex 1000000000\n" + vertex + faces + body);
    EXPECT_NE(e.find("element 'vertex' declares 1000000000 entries, more than the rest of the "
                     "file holds"),
              std::string::npos)
        << e;
    e = ply_error(header + "element vertex 3\n" + vertex + faces + body + face(2000000000, 0));
    EXPECT_NE(e.find("a list of 2e+09 items, more than the rest of the file holds"),
              std::string::npos)
        << e;
    e = ply_error(header + "element vertex 3\n" + vertex + faces + body + face(3, -1));
    EXPECT_NE(e.find("face index -1 out of range"), std::string::npos) << e;
}

TEST(Parser, TruncatedPlyIsAnError)
{
    ScratchDir dir("plybad");
    dir.write("t.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\nabc");
    const std::string e =
        error_of("WorldBegin\nShape \"plymesh\" \"string filename\" \"t.ply\"\n", dir.file(""));
    EXPECT_NE(e.find("t.pbrt:2:"), std::string::npos) << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
}
