// ParameterList: one directive's "type name" [values] parameters, typed lookups, the
// errors and warnings that name file:line.
#include <gtest/gtest.h>

#include "statmc/render/parameter_list.h"
#include "statmc/render/tokenizer.h"

using namespace statmc::render;

namespace {

/// The parameters of `text` (parameters only, no directive) as if they followed a
/// directive on line 1 of t.pbrt.
ParameterList parse(const std::string& text)
{
    const auto tokens = tokenize(text, "t.pbrt");
    std::size_t pos = 0;
    return ParameterList::parse(tokens, pos, "t.pbrt", 1);
}

template <class F>
std::string error_of(F&& f)
{
    try {
        f();
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(ParameterList, ParseStopsAtTheNextDirectiveAndCanonicalisesTypes)
{
    const auto tokens =
        tokenize("\"integer n\" 3 \"point3 P\" [0 1 2\n 3 4 5]\n\"color Kd\" [.5 .5 .5]\n"
                 "\"string s\" [\"a\"] \"bool b\" \"true\"\nWorldBegin\n",
                 "t.pbrt");
    std::size_t pos = 0;
    const ParameterList ps = ParameterList::parse(tokens, pos, "t.pbrt", 1);
    ASSERT_LT(pos, tokens.size());
    EXPECT_EQ(tokens[pos].text, "WorldBegin");
    ASSERT_EQ(ps.parameters().size(), 5u);
    EXPECT_EQ(ps.parameters()[1].type, "point");  // point3
    EXPECT_EQ(ps.parameters()[1].numbers.size(), 6u);
    EXPECT_EQ(ps.parameters()[2].type, "rgb");  // color
    EXPECT_EQ(ps.parameters()[2].line, 3);
    EXPECT_EQ(ps.parameters()[3].strings, std::vector<std::string>{"a"});
    EXPECT_EQ(ps.parameters()[4].strings, std::vector<std::string>{"true"});
    EXPECT_EQ(ps.file(), "t.pbrt");
    EXPECT_EQ(ps.line(), 1);
}

TEST(ParameterList, ParseErrorsNameFileAndLine)
{
    EXPECT_EQ(error_of([] { parse("\n\"integer\" 1"); }),
              "t.pbrt:2: malformed parameter declaration \"integer\" (expected \"type name\")");
    EXPECT_EQ(error_of([] { parse("\"quaternion q\" 1"); }),
              "t.pbrt:1: unknown parameter type 'quaternion' in \"quaternion q\"");
    EXPECT_EQ(error_of([] { parse("\"float f\" [1\n\"x\"]"); }),
              "t.pbrt:2: parameter \"float f\" expects numbers, got 'x'");
    EXPECT_EQ(error_of([] { parse("\"string s\" [1]"); }),
              "t.pbrt:1: parameter \"string s\" expects quoted strings");
    EXPECT_EQ(error_of([] { parse("\n\n\"float f\" [1 2"); }),
              "t.pbrt:3: missing ']' after parameter \"float f\"");
    EXPECT_EQ(error_of([] { parse("\"float f\""); }),
              "t.pbrt:1: parameter \"float f\" has no value");
}

TEST(ParameterList, TypedGettersReadOneValueOrNothing)
{
    ParameterList ps =
        parse("\"integer n\" [7] \"float f\" 0.25 \"bool b\" \"false\" \"string s\" \"x.exr\" "
              "\"rgb c\" [1 2 3]");
    EXPECT_EQ(ps.get_int("n"), 7);
    EXPECT_EQ(ps.get_float("f"), 0.25f);
    EXPECT_EQ(ps.get_bool("b"), false);
    EXPECT_EQ(ps.get_string("s"), std::string("x.exr"));
    const auto c = ps.get_rgb("c");
    ASSERT_TRUE(c);
    EXPECT_EQ(c->r, 1.f);
    EXPECT_EQ(c->b, 3.f);
    // Absent, or present with another type: nothing (the caller's default applies).
    EXPECT_FALSE(ps.get_int("missing"));
    EXPECT_FALSE(ps.get_float("n"));  // "n" is an integer
    EXPECT_FALSE(ps.get_rgb("f"));
    EXPECT_TRUE(ps.unused_warnings("Test").empty());
}

TEST(ParameterList, WrongArityIsAnErrorAtTheParametersLine)
{
    EXPECT_EQ(error_of([] { parse("\n\"integer n\" [1 2]").get_int("n"); }),
              "t.pbrt:2: \"integer n\" needs one value");
    EXPECT_EQ(error_of([] { parse("\"float f\" []").get_float("f"); }),
              "t.pbrt:1: \"float f\" needs one value");
    EXPECT_EQ(error_of([] { parse("\n\n\"string s\" [\"a\" \"b\"]").get_string("s"); }),
              "t.pbrt:3: \"string s\" needs one value");
    EXPECT_EQ(error_of([] { parse("\"rgb c\" [1 2]").get_rgb("c"); }),
              "t.pbrt:1: \"rgb c\" needs three values");
    EXPECT_EQ(error_of([] { parse("\"bool b\" \"yes\"").get_bool("b"); }),
              "t.pbrt:1: \"bool b\" must be \"true\" or \"false\"");
    EXPECT_EQ(error_of([] { parse("\"spectrum L\" [400 1 700 1]").get_rgb("L"); }),
              "t.pbrt:1: unsupported: \"spectrum L\" (only rgb colours are supported)");
}

TEST(ParameterList, RawAccessForArrays)
{
    ParameterList ps = parse(
        "\"point P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2] \"float uv\" [0 0 1 0 0 1]");
    const Parameter* P = ps.find("point", "P");
    ASSERT_TRUE(P);
    EXPECT_EQ(P->numbers.size(), 9u);
    EXPECT_TRUE(P->used);
    EXPECT_FALSE(ps.find("normal", "N"));
    EXPECT_FALSE(ps.find("float", "P"));  // the type is part of the key
    // find_any looks by name alone and leaves the parameter unused.
    const Parameter* uv = ps.find_any("uv");
    ASSERT_TRUE(uv);
    EXPECT_EQ(uv->type, "float");
    EXPECT_FALSE(uv->used);
    const auto w = ps.unused_warnings("Shape \"trianglemesh\"");
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0], "t.pbrt:1: warning: unknown parameter \"integer indices\" of Shape "
                    "\"trianglemesh\" ignored");
    EXPECT_EQ(
        w[1],
        "t.pbrt:1: warning: unknown parameter \"float uv\" of Shape \"trianglemesh\" ignored");
}

TEST(ParameterList, UnusedParametersWarnInFileOrder)
{
    ParameterList ps = parse("\"float wobble\" 3\n\"float radius\" 1\n\"integer n\" 2\n");
    EXPECT_EQ(ps.get_float("radius"), 1.f);
    const auto w = ps.unused_warnings("Shape \"sphere\"");
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w[0],
              "t.pbrt:1: warning: unknown parameter \"float wobble\" of Shape \"sphere\" ignored");
    EXPECT_EQ(w[1],
              "t.pbrt:3: warning: unknown parameter \"integer n\" of Shape \"sphere\" ignored");
}

TEST(ParameterList, IgnoreMarksUsedWithOrWithoutAWarning)
{
    ParameterList quiet =
        parse("\"bool trilinear\" \"true\" \"float maxanisotropy\" 8 \"float other\" 1");
    EXPECT_TRUE(quiet.ignore({"trilinear", "maxanisotropy", "wrap"}).empty());
    const auto w = quiet.unused_warnings("Texture");
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("\"float other\""), std::string::npos) << w[0];

    // With a warning: one per parameter present, names in the order given, any type.
    ParameterList loud = parse("\"float screenwindow\" [-1 1 -1 1]\n\"float lensradius\" 0.1\n"
                               "\"integer lensradius\" 2\n");
    const auto ignored =
        loud.ignore({"lensradius", "focaldistance", "screenwindow"}, "Camera parameter");
    ASSERT_EQ(ignored.size(), 3u);
    EXPECT_EQ(ignored[0],
              "t.pbrt:2: warning: Camera parameter \"lensradius\" not supported, ignored");
    EXPECT_EQ(ignored[1],
              "t.pbrt:3: warning: Camera parameter \"lensradius\" not supported, ignored");
    EXPECT_EQ(ignored[2],
              "t.pbrt:1: warning: Camera parameter \"screenwindow\" not supported, ignored");
    EXPECT_TRUE(loud.unused_warnings("Camera").empty());
}

TEST(ParameterList, ErrorsAndWarningsNameTheDirectiveByDefault)
{
    const ParameterList ps("scene.pbrt", 12);
    EXPECT_EQ(ps.warning("x"), "scene.pbrt:12: warning: x");
    EXPECT_EQ(ps.warning(3, "y"), "scene.pbrt:3: warning: y");
    EXPECT_EQ(error_of([&] { ps.error("bad"); }), "scene.pbrt:12: bad");
    EXPECT_EQ(error_of([&] { ps.error(4, "worse"); }), "scene.pbrt:4: worse");
}
