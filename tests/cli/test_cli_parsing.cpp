// The command-line pieces on their own: strict numbers, modifiers, splitting.
#include <gtest/gtest.h>

#include "statmc/plugin_host/host_error.h"
#include "statmc/plugin_host/number_parsing.h"
#include "statmc/tool/command_line.h"
#include "statmc/tool/command_table.h"

namespace statmc::tool {
namespace {

TEST(CliParsing, IntegersAreWholeTokens)
{
    EXPECT_EQ(host::parse_int("20", "radius"), 20);
    EXPECT_EQ(host::parse_int("-3", "radius"), -3);
    for (const char* bad : {"", "abc", "3x", "3.0", " 3", "+3", "99999999999"})
        EXPECT_THROW(host::parse_int(bad, "radius"), host::HostError) << bad;
}

TEST(CliParsing, FloatsAreFiniteWholeTokens)
{
    EXPECT_EQ(host::parse_float("0.005", "alpha"), 0.005);
    EXPECT_EQ(host::parse_float("1e-3", "alpha"), 1e-3);
    EXPECT_EQ(host::parse_float("10", "sigma_s"), 10.0);
    for (const char* bad : {"", "x", "0.1.2", "inf", "nan", "1e999", "0,5"})
        EXPECT_THROW(host::parse_float(bad, "alpha"), host::HostError) << bad;
}

TEST(CliParsing, CommandWordsSplitIntoNameAndModifiers)
{
    const auto [name, mods] = split_command("--denoise:radius=3:guides=albedo,normal");
    EXPECT_EQ(name, "--denoise");
    ASSERT_EQ(mods.size(), 2u);
    EXPECT_EQ(mods[0], (std::pair<std::string, std::string>{"radius", "3"}));
    EXPECT_EQ(mods[1], (std::pair<std::string, std::string>{"guides", "albedo,normal"}));
    EXPECT_THROW(split_command("--denoise::radius=3"), host::HostError);
    EXPECT_THROW(split_command("--denoise:=3"), host::HostError);
}

TEST(CliParsing, InvocationsConsumeTheirArguments)
{
    const std::vector<std::string> args = {"a.exr", "--denoise:radius=7", "-o", "b.exr"};
    std::size_t i = 0;
    const Invocation input = parse_invocation(args, i);
    EXPECT_EQ(input.name, "-i");
    EXPECT_EQ(input.args, (std::vector<std::string>{"a.exr"}));
    const Invocation denoise = parse_invocation(args, i);
    EXPECT_EQ(denoise.modifiers.get_int("radius"), 7);
    EXPECT_EQ(denoise.modifiers.get_float("alpha"), 0.005);  // default filled in
    EXPECT_EQ(denoise.modifiers.get_list("guides"), (std::vector<std::string>{"auto"}));
    const Invocation output = parse_invocation(args, i);
    EXPECT_EQ(output.args, (std::vector<std::string>{"b.exr"}));
    EXPECT_EQ(i, args.size());
}

TEST(CliParsing, TheTableKnowsItsCommandsAndAliases)
{
    for (const char* name :
         {"-i", "-o", "--denoise", "--passes", "--threads", "--help", "-h", "--version"})
        EXPECT_TRUE(find_command(name)) << name;
    EXPECT_FALSE(find_command("--denoize"));
    EXPECT_EQ(find_command("-h"), find_command("--help"));
}

}  // namespace
}  // namespace statmc::tool
