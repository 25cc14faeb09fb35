// The CUDA path against the CPU path (docs/gpu.md): the same membership decisions, values
// within 1e-5 relative (only the order of the sums differs), the same bits run to run. On a
// machine without a GPU every test that needs one reports itself skipped, by name, with
// the reason; ctest counts them as skipped (label `cuda`).
#include <cmath>
#include <cstring>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "filter_fixtures.h"
#include "filter_layout.h"
#include "statmc/core/cuda_device.h"
#include "statmc/core/filter.h"

namespace statmc {
namespace {

#define REQUIRE_GPU()                                                                              \
    do {                                                                                           \
        std::string why;                                                                           \
        if (!cuda_available(&why))                                                                 \
            GTEST_SKIP() << "needs a CUDA GPU: " << why;                                           \
    } while (0)

// What docs/gpu.md promises: the same members, values within 1e-5 relative.
void expect_same_members_close_values(const Output& gpu, const Output& cpu)
{
    expect_same_members(gpu, cpu, {1e-5f, 1e-5f, 1e-4f});
}

class CudaVsCpu : public ::testing::TestWithParam<FilterCase> {};

TEST_P(CudaVsCpu, SameMembersAndValues)
{
    REQUIRE_GPU();
    const FilterCase k = GetParam();
    // random_estimators holds untestable (NaN-variance) pixels and fireflies, so the guard
    // and the never-a-member padding are compared too.
    const EstimatorImage est = random_estimators(k.w, k.h, k.channels, 300 + k.w + k.radius);
    GuideImages g(k.w, k.h, k.albedo, k.normal, 9, k.guide_noise);
    DenoiseOptions opt = case_options(k);
    Output cpu(k.w, k.h, k.channels), gpu(k.w, k.h, k.channels);
    filter(est, g.guides, opt, cpu.planes(), cpu.diagnostics());
    opt.device = Device::Cuda;
    filter(est, g.guides, opt, gpu.planes(), gpu.diagnostics());
    expect_same_members_close_values(gpu, cpu);
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, CudaVsCpu,
    // And r = 20 over several blocks, with and without guides, and r = 400, whose 17
    // staged planes of 832 floats need more than the 48 KB a block gets unasked.
    ::testing::ValuesIn(filter_cases({{70, 45, 3, 20, false, false},
                                      {70, 45, 3, 20, true, true},
                                      {900, 30, 3, 400, true, true}})),
    case_name);

TEST(Cuda, WithoutDiagnosticsTheValuesAgreeToo)
{
    // The production call: no diagnostics, so no 1/n plane is staged and no count is kept.
    REQUIRE_GPU();
    const EstimatorImage est = random_estimators(83, 51, 3, 17);
    GuideImages g(83, 51, true, true, 3);
    DenoiseOptions opt;
    Output cpu(83, 51, 3), gpu(83, 51, 3);
    filter(est, g.guides, opt, cpu.planes());
    opt.device = Device::Cuda;
    filter(est, g.guides, opt, gpu.planes());
    for (std::size_t i = 0; i < cpu.values.size(); ++i)
        ASSERT_NEAR(gpu.values[i], cpu.values[i], 1e-5f * (1 + std::abs(cpu.values[i])))
            << "value " << i;
}

TEST(Cuda, SameBitsRunToRun)
{
    REQUIRE_GPU();
    const EstimatorImage est = random_estimators(150, 97, 3, 31);
    GuideImages g(150, 97, true, true, 4);
    DenoiseOptions opt;
    opt.device = Device::Cuda;
    Output a(150, 97, 3), b(150, 97, 3);
    filter(est, g.guides, opt, a.planes(), a.diagnostics());
    filter(est, g.guides, opt, b.planes(), b.diagnostics());
    EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * 4), 0);
    EXPECT_EQ(std::memcmp(a.effective.data(), b.effective.data(), a.effective.size() * 4), 0);
}

TEST(Cuda, RadiusLadderRungsMatchTheCpuRungs)
{
    // The rungs' sums stay on the device between rungs (each adds its annulus).
    REQUIRE_GPU();
    const EstimatorImage est = random_estimators(61, 37, 3, 41);
    GuideImages g(61, 37, true, true, 6);
    DenoiseOptions opt;
    opt.radius = 12;
    const std::vector<int> radii = {1, 2, 3, 5, 8, 12};
    std::vector<Output> cpu;
    Output out(61, 37, 3);
    detail::filter_rungs(est, g.guides, opt, radii, out.planes(), out.diagnostics(), 0,
                         SimdLevel::Auto, [&](int) { cpu.push_back(out); });
    opt.device = Device::Cuda;
    std::size_t rung = 0;
    detail::filter_rungs(est, g.guides, opt, radii, out.planes(), out.diagnostics(), 0,
                         SimdLevel::Auto, [&](int radius) {
                             SCOPED_TRACE("radius " + std::to_string(radius));
                             ASSERT_LT(rung, cpu.size());
                             expect_same_members_close_values(out, cpu[rung++]);
                         });
    EXPECT_EQ(rung, radii.size());
}

TEST(Cuda, DeviceCudaRunsOrIsAClearErrorAndSmallImagesStayOnTheCpu)
{
    const EstimatorImage est = random_estimators(16, 16, 3, 1);
    DenoiseOptions opt;
    opt.device = Device::Cuda;
    Output out(16, 16, 3), cpu(16, 16, 3);
    filter(est, {}, DenoiseOptions{}, cpu.planes());
    std::string why;
    if (cuda_available(&why)) {  // a GPU is here: it runs, and says which
        EXPECT_FALSE(cuda_device_description().empty());
        filter(est, {}, opt, out.planes());
        for (std::size_t i = 0; i < cpu.values.size(); ++i)
            ASSERT_NEAR(out.values[i], cpu.values[i], 1e-5f * (1 + std::abs(cpu.values[i])));
    } else {
        EXPECT_FALSE(why.empty());
        EXPECT_TRUE(cuda_device_description().empty());
        try {
            filter(est, {}, opt, out.planes());
            FAIL() << "device=cuda ran without a GPU";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), "device=cuda: " + why);
        }
    }
    // auto leaves an image below kAutoCudaPixels on the CPU, bit for bit, GPU or not.
    opt.device = Device::Auto;
    filter(est, {}, opt, out.planes());
    EXPECT_EQ(out.values, cpu.values);
}

}  // namespace
}  // namespace statmc
