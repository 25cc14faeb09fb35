// The multi-input check that passes and merge share: frame, channel names, and how an
// input is named in the message.
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/frame_match.h"
#include "statmc/layers/layer_error.h"

namespace {

OIIO::ImageBuf image(int w, int h, const std::vector<std::string>& channels,
                     const std::string& name = "")
{
    OIIO::ImageSpec spec(w, h, int(channels.size()), OIIO::TypeFloat);
    spec.channelnames = channels;
    return OIIO::ImageBuf(name, spec);
}

std::string message_of(const std::vector<const OIIO::ImageBuf*>& inputs)
{
    try {
        statmc::layers::require_matching_inputs(inputs, "render");
    } catch (const statmc::layers::LayerError& e) {
        return e.what();
    }
    return "";
}

TEST(FrameMatch, LabelNamesTheFileWhenThereIsOne)
{
    const OIIO::ImageBuf named = image(2, 2, {"R"}, "a.exr"), unnamed = image(2, 2, {"R"});
    EXPECT_EQ(statmc::layers::input_label("render", 3, &named), "render 3 (a.exr)");
    EXPECT_EQ(statmc::layers::input_label("part", 0, &unnamed), "part 0");
    EXPECT_EQ(statmc::layers::input_label("part", 1, nullptr), "part 1");
}

TEST(FrameMatch, SameChannelsInAnotherOrderMatch)
{
    const OIIO::ImageBuf a = image(4, 3, {"R", "G", "B"}), b = image(4, 3, {"B", "R", "G"});
    EXPECT_EQ(message_of({&a, &b}), "");
}

TEST(FrameMatch, NamesTheChannelsOnlyOneSideHas)
{
    const OIIO::ImageBuf a = image(4, 3, {"R", "G", "B"}, "a.exr"),
                         b = image(4, 3, {"R", "G", "A"}, "b.exr");
    EXPECT_EQ(
        message_of({&a, &b}),
        "render 1 (b.exr) and render 0 (a.exr) differ in channels: only in render 1 (b.exr): A; "
        "only in render 0 (a.exr): B");
    const OIIO::ImageBuf c = image(4, 3, {"R", "G", "B", "Z"});
    EXPECT_EQ(message_of({&a, &c}), "render 1 and render 0 (a.exr) differ in channels: only in "
                                    "render 1: Z; only in render 0 (a.exr): none");
}

TEST(FrameMatch, ResolutionAndOriginComeFirst)
{
    const OIIO::ImageBuf a = image(4, 3, {"R"}), b = image(4, 3, {"G"}), wide = image(5, 3, {"G"});
    OIIO::ImageBuf moved = image(4, 3, {"R"});
    moved.set_origin(1, 2);
    EXPECT_EQ(message_of({&a, &a, &wide}),
              "render 2 and render 0 differ in resolution: 5x3 vs 4x3");
    EXPECT_EQ(message_of({&a, &moved, &b}),
              "render 1 and render 0 differ in data window: origin (1, 2) vs (0, 0)");
}

}  // namespace
