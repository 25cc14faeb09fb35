// The plugin interface on its own: parameter ranges, loading a module, refusing one
// built against another interface version.
#include <algorithm>
#include <cmath>
#include <tuple>

#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/plugin_sdk/plugin_interface.h"
#include "statmc/plugin_sdk/plugin_loader.h"

namespace statmc {
namespace {

const std::string kGood = std::string(STATMC_TEST_MODULE_DIR) + "/good/testscale.so";
const std::string kWrong = std::string(STATMC_TEST_MODULE_DIR) + "/wrong/wrong_version.so";

// The message of the PluginError `f` throws, or "" when it throws none.
template <class F>
std::string error_of(F&& f)
{
    try {
        f();
    } catch (const PluginError& e) {
        return e.what();
    }
    return {};
}

TEST(PluginApi, RangesDescribeAndCheckThemselves)
{
    const ParameterSpec radius = int_parameter("radius", 20, "").between(0, 1000);
    EXPECT_EQ(radius.range.text(), "[0, 1000]");
    EXPECT_EQ(radius.range.violation("radius", 1000), "");
    EXPECT_EQ(radius.range.violation("radius", -1), "radius must be in [0, 1000], got -1");
    const ParameterSpec alpha = float_parameter("alpha", 0.005, "").open_between(0, 1);
    EXPECT_EQ(alpha.default_value, "0.005");
    EXPECT_EQ(alpha.range.violation("alpha", 1), "alpha must be in (0, 1), got 1");
    EXPECT_EQ(float_parameter("s", 10, "").above(0).range.violation("s", 0),
              "s must be > 0, got 0");
    EXPECT_EQ(int_parameter("n", std::nullopt, "").at_least(2).range.violation("n", 1),
              "n must be at least 2, got 1");
    EXPECT_EQ(int_parameter("n", std::nullopt, "").default_value, "");
}

TEST(PluginApi, StringsAreNamesUnlessWrittenOtherwise)
{
    EXPECT_EQ(string_parameter("aov", "", "").value_syntax(), "name");
    EXPECT_EQ(string_parameter("radii", "1,2", "").written_as("int,int,...").value_syntax(),
              "int,int,...");
    EXPECT_EQ(int_parameter("n", 1, "").value_syntax(), "int");
}

TEST(PluginApi, ValuesFallBackToTheirDefaults)
{
    ParameterValues values;
    values.set("radius", 7);
    EXPECT_EQ(values.get_int("radius", 20), 7);
    EXPECT_EQ(values.get_float("alpha", 0.005), 0.005);
    EXPECT_EQ(values.get_list("guides", {"auto"}), std::vector<std::string>{"auto"});
}

TEST(PluginApi, SearchPathsSplitOnColons)
{
    EXPECT_EQ(split_search_path("a:b::/c/d:"), (std::vector<std::string>{"a", "b", "/c/d"}));
    EXPECT_TRUE(split_search_path("").empty());
}

TEST(PluginApi, LoadsAModuleAndRunsItsOperator)
{
    PluginRegistry registry;
    load_plugin(kGood, registry);
    const OperatorSpec* op = registry.find("testscale");
    ASSERT_TRUE(op);
    EXPECT_EQ(op->module, kGood);
    EXPECT_EQ(op->inputs, 1);
    ASSERT_EQ(op->parameters.size(), 2u);
    EXPECT_EQ(op->parameters[0].range.text(), "[0.01, 100]");
    EXPECT_EQ(op->parameters[1].type, ParameterType::Bool);

    OIIO::ImageBuf in(OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::FLOAT));
    const float px[3] = {1.f, 2.f, 4.f};
    OIIO::ImageBufAlgo::fill(in, px);
    ParameterValues values;
    values.set("factor", 3.0);
    const OIIO::ImageBuf out = op->run({&in}, values, RunContext{});
    ASSERT_FALSE(out.has_error()) << out.geterror();
    EXPECT_FLOAT_EQ(out.getchannel(1, 1, 0, 2), 12.f);
    values.set("reciprocal", true);
    EXPECT_FLOAT_EQ(op->run({&in}, values, RunContext{}).getchannel(0, 0, 0, 1), 2.f / 3.f);
}

TEST(PluginApi, RefusesAModuleOfAnotherInterfaceVersion)
{
    PluginRegistry registry;
    const std::string message = error_of([&] { load_plugin(kWrong, registry); });
    EXPECT_NE(message.find(kWrong + ": plugin interface version " +
                           std::to_string(kPluginInterfaceVersion + 41)),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("needs version " + std::to_string(kPluginInterfaceVersion)),
              std::string::npos)
        << message;
    EXPECT_TRUE(registry.operators().empty());
}

TEST(PluginApi, RefusesAModuleBuiltDifferently)
{
    const std::string module =
        std::string(STATMC_TEST_MODULE_DIR) + "/wrong_identity/wrong_identity.so";
    PluginRegistry registry;
    const std::string message = error_of([&] { load_plugin(module, registry); });
    EXPECT_NE(message.find(module + ": built differently from this statmc: "), std::string::npos)
        << message;
    EXPECT_TRUE(registry.operators().empty());
}

TEST(PluginApi, BuildIdentityNamesEachDifference)
{
    const BuildIdentity host = this_build_identity();
    EXPECT_EQ(build_identity_mismatch(host, host), "");
    EXPECT_EQ(host.oiio_version, OIIO_VERSION);
    EXPECT_EQ(host.sizeof_image_buf, int(sizeof(OIIO::ImageBuf)));

    BuildIdentity other = host;
    other.oiio_version = 20500;
    other.cxx11_abi = 1 - host.cxx11_abi;
    other.sizeof_operator_spec = host.sizeof_operator_spec + 8;
    const std::string oiio = std::to_string(OIIO_VERSION_MAJOR) + "." +
                             std::to_string(OIIO_VERSION_MINOR) + "." +
                             std::to_string(OIIO_VERSION_PATCH);
    EXPECT_EQ(build_identity_mismatch(other, host),
              "OpenImageIO 2.5.0 (this statmc: " + oiio +
                  "), _GLIBCXX_USE_CXX11_ABI=" + std::to_string(other.cxx11_abi) +
                  " (this statmc: " + std::to_string(host.cxx11_abi) +
                  "), sizeof(statmc::OperatorSpec) " + std::to_string(other.sizeof_operator_spec) +
                  " (this statmc: " + std::to_string(host.sizeof_operator_spec) + ")");
}

TEST(PluginApi, ReportsUnloadableFilesAndDuplicates)
{
    PluginRegistry registry;
    const std::string missing = std::string(STATMC_TEST_MODULE_DIR) + "/none.so";
    EXPECT_NE(
        error_of([&] { load_plugin(missing, registry); }).find(missing + ": cannot load plugin: "),
        std::string::npos);
    load_plugin(kGood, registry);
    EXPECT_NE(error_of([&] {
                  load_plugin(kGood, registry);
              }).find("operator 'testscale' is already registered by " + kGood),
              std::string::npos);
    EXPECT_EQ(registry.operators().size(), 3u);  // testscale, testthrow, testthrowinplace
}

TEST(PluginApi, ListsModulesOfADirectory)
{
    EXPECT_EQ(plugin_files(std::string(STATMC_TEST_MODULE_DIR) + "/good"),
              std::vector<std::string>{kGood});
    EXPECT_TRUE(plugin_files(std::string(STATMC_TEST_MODULE_DIR) + "/absent").empty());
}

}  // namespace
}  // namespace statmc

namespace statmc {
namespace {

TEST(PluginApi, EveryShippedOperatorAcceptsTheBoundsItsTableStates)
{
    // A parameter's range in the table (what --help prints and the host enforces) and the
    // operator's own validation must agree: a value at an inclusive bound, or just inside
    // an exclusive one, passes both.
    PluginRegistry registry;
    for (const std::string& file : plugin_files(STATMC_PLUGIN_DIR))
        load_plugin(file, registry);
    ASSERT_GE(registry.operators().size(), 7u);
    int checked = 0;
    for (const OperatorSpec& op : registry.operators()) {
        for (const ParameterSpec& spec : op.parameters) {
            if (spec.type != ParameterType::Int && spec.type != ParameterType::Float)
                continue;
            const ParameterRange& r = spec.range;
            for (const auto& [bound, exclusive, inward] :
                 {std::tuple{r.min, r.min_exclusive, 1.0},
                  std::tuple{r.max, r.max_exclusive, -1.0}}) {
                if (!bound)
                    continue;
                const bool whole = spec.type == ParameterType::Int;
                const double step = whole ? 1.0 : 1e-6 * std::max(1.0, std::abs(*bound));
                const double value = exclusive ? *bound + inward * step : *bound;
                EXPECT_EQ(r.violation(spec.name, value), "") << op.name << ":" << spec.name;
                ParameterValues p;
                p.set(spec.name, whole ? ParameterValue(int(value)) : ParameterValue(value));
                if (op.check) {
                    EXPECT_EQ(op.check(p), "") << "--" << op.name << ":" << spec.name << "="
                                               << value << " is inside " << r.text();
                }
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 15);  // the bounds of every shipped operator, not a few
}

}  // namespace
}  // namespace statmc
