// Frame lists and patterns as oiiotool spells them, and the bound on what a list may ask for.
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/layers/frame_names.h"

namespace {

using statmc::layers::frame_list;
using statmc::layers::kMaxFrames;

TEST(FrameNames, ListsReadAsOiiotoolReadsThem)
{
    EXPECT_EQ(*frame_list("3"), (std::vector<int>{3}));
    EXPECT_EQ(*frame_list("1-4"), (std::vector<int>{1, 2, 3, 4}));
    EXPECT_EQ(*frame_list("1-9x4"), (std::vector<int>{1, 5, 9}));
    EXPECT_EQ(*frame_list("1-5y2"), (std::vector<int>{2, 4}));
    EXPECT_EQ(*frame_list("4-1"), (std::vector<int>{4, 3, 2, 1}));
    EXPECT_EQ(*frame_list("3,5,10-12"), (std::vector<int>{3, 5, 10, 11, 12}));
}

TEST(FrameNames, MalformedListsAreRefused)
{
    for (const char* bad : {"", "two", "1-", "-3", "1--3", "1,,2", "1-4z2", "1-4x", "1-4x2x", " 1",
                            "1-4 ", "1234567890"})
        EXPECT_FALSE(frame_list(bad)) << "'" << bad << "'";
}

TEST(FrameNames, AListMaySpanAtMostKMaxFramesWhateverItsStep)
{
    // OIIO walks every number between a range's ends, so a step does not shrink the walk.
    EXPECT_EQ(frame_list("1-" + std::to_string(kMaxFrames))->size(), std::size_t(kMaxFrames));
    EXPECT_FALSE(frame_list("1-" + std::to_string(kMaxFrames + 1)));
    EXPECT_FALSE(frame_list("1-999999999x1000000"));
    EXPECT_FALSE(frame_list("1-600000,1-600000"));
}

TEST(FrameNames, PatternsAndPaths)
{
    std::string range;
    EXPECT_EQ(statmc::layers::frame_pattern("shot.#.exr"), "shot.%04d.exr");
    EXPECT_EQ(statmc::layers::frame_pattern("shot.@@@.exr"), "shot.%03d.exr");
    EXPECT_EQ(statmc::layers::frame_pattern("shot.1-10#.exr", &range), "shot.%04d.exr");
    EXPECT_EQ(range, "1-10");
    EXPECT_EQ(statmc::layers::frame_pattern("shot.exr"), "");
    EXPECT_EQ(statmc::layers::frame_path("shot.%04d.exr", 7), "shot.0007.exr");
}

TEST(FrameNames, APatternPadsToAtMostKMaxFramePaddingDigits)
{
    using statmc::layers::kMaxFramePadding;
    EXPECT_EQ(statmc::layers::frame_pattern("s.%0" + std::to_string(kMaxFramePadding) + "d.exr"),
              "s.%0" + std::to_string(kMaxFramePadding) + "d.exr");
    for (const std::string& wide : {"s.%0" + std::to_string(kMaxFramePadding + 1) + "d.exr",
                                    std::string("s.%0999999999d.exr"),
                                    "s." + std::string(kMaxFramePadding + 1, '#') + ".exr"}) {
        try {
            statmc::layers::frame_pattern(wide);
            ADD_FAILURE() << wide << " was accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(wide + ": a frame pattern pads to at most 32"),
                      std::string::npos)
                << e.what();
        }
    }
}

}  // namespace
