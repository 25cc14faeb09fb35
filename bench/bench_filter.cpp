// Filter speed at the reference size: a 1280×720 RGB frame (a typical HD render), r = 20,
// α = 0.005, n = 64.
// Reports the median over repetitions and pixel-taps per second (taps = window pixels
// tested per output pixel, summed over the image).
#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>

#include <benchmark/benchmark.h>

#include "bench_frame.h"
#include "bench_timing.h"
#include "statmc/core/filter.h"
#include "statmc/core/method.h"
#include "statmc/core/variance_filter.h"

namespace {

using namespace statmc;
using bench::kHeight;
using bench::kWidth;

double taps_per_image(int width, int height, int radius)
{
    // Window pixels inside the image, summed over all pixels (what the filter tests).
    double taps = 0;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if (dx * dx + dy * dy <= radius * radius && (dx || dy))
                taps +=
                    double(std::max(0, width - std::abs(dx))) * std::max(0, height - std::abs(dy));
    return taps;
}

/// The default options (α = 0.005) with the firefly guard off.
DenoiseOptions no_guard()
{
    DenoiseOptions o;
    o.firefly_ratio = 0;
    return o;
}

/// The default options at radius 0.
DenoiseOptions radius_zero()
{
    DenoiseOptions o;
    o.radius = 0;
    return o;
}

void run(benchmark::State& state, bool with_guides, SimdLevel level, bool reference,
         const DenoiseOptions& options = {}, bool fireflies = false, bool guide_noise = false)
{
    EstimatorImage est =
        estimators_from_statistics(bench::frame(fireflies).view(), TestDomain::BoxCox);
    if (reference)
        // Its cost per tap does not depend on the size: a corner, compared in taps/s.
        est = bench::tiled(est, kWidth / 4, kHeight / 4);
    static const bench::GuidePlanes guide_planes;
    static const bench::GuidePlanes noisy_guide_planes(kWidth, kHeight, /*noise=*/true);
    const Guides guides = !with_guides  ? Guides{}
                          : guide_noise ? noisy_guide_planes.guides
                                        : guide_planes.guides;
    std::vector<float> out(est.value.size());
    std::vector<Plane> planes;
    for (int c = 0; c < 3; ++c)
        planes.push_back(dense_plane(out.data() + c * est.pixels(), est.width));
    for (auto _ : state) {
        if (reference)
            filter_reference(est, guides, options, planes);
        else
            filter(est, guides, options, planes, {}, int(state.range(0)), level);
        benchmark::DoNotOptimize(out.data());
    }
    state.counters["taps/s"] = benchmark::Counter(
        taps_per_image(est.width, est.height, options.radius) * state.iterations(),
        benchmark::Counter::kIsRate);
    std::string label =
        reference ? "reference (double, 1 thread, 320x180 crop)" : simd_level_name(level);
    if (options.firefly_ratio == 0)
        label += ", no firefly guard";
    if (fireflies)
        label += ", 1 pixel in 500 a firefly";
    if (options.radius == 0)
        label += ", r = 0: the per-call cost outside the window walk";
    state.SetLabel(label);
}

void BM_Filter(benchmark::State& s) { run(s, false, detected_simd_level(), false); }
void BM_FilterGuides(benchmark::State& s) { run(s, true, detected_simd_level(), false); }
// The guides with their variances: the kernel's guide-noise loop.
void BM_FilterGuideNoise(benchmark::State& s)
{
    run(s, true, detected_simd_level(), false, {}, false, /*guide_noise=*/true);
}
void BM_FilterNoGuard(benchmark::State& s)
{
    run(s, false, detected_simd_level(), false, no_guard());
}
void BM_FilterFireflies(benchmark::State& s)
{
    run(s, s.range(1) != 0, detected_simd_level(), false, {}, true);
}
void BM_FilterFixedCost(benchmark::State& s)
{
    run(s, s.range(1) != 0, detected_simd_level(), false, radius_zero());
}
void BM_FilterAvx2Kernel(benchmark::State& s)
{
    const std::vector<SimdLevel> levels = supported_simd_levels();
    if (std::find(levels.begin(), levels.end(), SimdLevel::Avx2) == levels.end()) {
        s.SkipWithError("no AVX2 on this CPU");
        return;
    }
    run(s, s.range(1) != 0, SimdLevel::Avx2, false);
}
void BM_FilterScalarKernel(benchmark::State& s) { run(s, false, SimdLevel::Scalar, false); }
void BM_FilterReference(benchmark::State& s) { run(s, false, SimdLevel::Scalar, true); }
void BM_FilterReferenceGuides(benchmark::State& s) { run(s, true, SimdLevel::Scalar, true); }

// The default's variance denoising (the radius ladder's ṽ as method_settings gives it:
// radius 3, moderation d₀ = 16 towards neighbours that pass the test on the means at
// α = 0.05, a pixel's own degrees of freedom from the scatter of ln s²) at one SIMD level;
// Args: guides (0/1), level (1 scalar, 2 AVX2, 3 AVX-512). All threads.
void BM_VarianceFilter(benchmark::State& state)
{
    const SimdLevel level = SimdLevel(state.range(1));
    const std::vector<SimdLevel> levels = supported_simd_levels();
    if (std::find(levels.begin(), levels.end(), level) == levels.end()) {
        state.SkipWithError("this CPU cannot run that level");
        return;
    }
    static const bench::GuidePlanes guide_planes;
    const Guides guides = state.range(0) ? guide_planes.guides : Guides{};
    const VarianceFilterOptions options = method_settings(Method::Default).stages.ladder.variance;
    for (auto _ : state)
        benchmark::DoNotOptimize(denoise_variances(bench::frame().view(), TestDomain::Untransformed,
                                                   guides, options, 0, level));
    state.SetLabel(simd_level_name(level));
}

// Arg = threads (0 = all cores). Medians over 5 repetitions (3 for the slow paths).
BENCHMARK(BM_Filter)->Arg(0)->Arg(1)->Apply(median_of_5);
BENCHMARK(BM_FilterGuides)->Arg(0)->Arg(1)->Apply(median_of_5);
BENCHMARK(BM_FilterGuideNoise)->Arg(1)->Apply(median_of_5);
BENCHMARK(BM_FilterNoGuard)->Arg(0)->Arg(1)->Apply(median_of_5);
// Args: threads, guides (0/1).
BENCHMARK(BM_FilterFireflies)->Args({0, 0})->Args({0, 1})->Apply(median_of_5);
BENCHMARK(BM_FilterFixedCost)->Args({0, 0})->Args({0, 1})->Apply(median_of_5);
BENCHMARK(BM_FilterAvx2Kernel)->Args({0, 0})->Args({0, 1})->Apply(median_of_5);
BENCHMARK(BM_FilterScalarKernel)->Arg(0)->Apply(median_of_3);
BENCHMARK(BM_FilterReference)->Arg(1)->Apply(median_of_3_single);
BENCHMARK(BM_FilterReferenceGuides)->Arg(1)->Apply(median_of_3_single);
BENCHMARK(BM_VarianceFilter)
    ->ArgsProduct({{0, 1}, {int(SimdLevel::Scalar), int(SimdLevel::Avx2), int(SimdLevel::Avx512)}})
    ->Apply(median_of_5);

}  // namespace

BENCHMARK_MAIN();
