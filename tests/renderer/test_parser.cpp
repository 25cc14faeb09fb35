#include <gtest/gtest.h>

#include "scene_parser.h"
#include "tokenizer.h"

using namespace statmc::render;

TEST(Parser, Placeholder) { EXPECT_NO_THROW(parse_scene_string("WorldBegin\nWorldEnd\n", "t.pbrt")); }
