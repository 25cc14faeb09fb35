// The filter on a CUDA GPU against the CPU in the same run (docs/gpu.md): r = 20, the
// benchmark frame's estimators (bench_frame.h, 1280×720 at n = 64) tiled to 1920×1080 and
// 3840×2160, with and without albedo + normal guides.
//
// - BM_CudaKernel: the kernel alone, timed by CUDA events (manual time), with the upload of
//   the layout and the download of the output as counters (ms).
// - BM_CudaFilter: filter() with device=cuda, end to end on planes in memory: the layout
//   built on the host, upload, kernel, download.
// - BM_CpuFilter: filter() on the CPU, for the ratio.
// Where no GPU is present the GPU benchmarks stop with an error that says why.
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_frame.h"
#include "bench_timing.h"
#include "filter_cuda.h"
#include "filter_layout.h"
#include "statmc/core/cuda_device.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"

namespace {

using namespace statmc;

struct Frame {
    EstimatorImage est;
    bench::GuidePlanes guide;
    std::vector<float> out;
    std::vector<Plane> planes;
    Frame(int width, int height)
        : est(bench::tiled(estimators_from_statistics(bench::frame().view(), TestDomain::BoxCox),
                           width, height)),
          guide(width, height), out(est.value.size())
    {
        for (int c = 0; c < est.channels; ++c)
            planes.push_back(dense_plane(out.data() + c * est.pixels(), width));
    }
};

const Frame& frame_of(int width)
{
    static const Frame hd(1280, 720), full_hd(1920, 1080), uhd(3840, 2160);
    return width == 1280 ? hd : width == 1920 ? full_hd : uhd;
}

bool skip_without_gpu(benchmark::State& state)
{
    std::string why;
    if (cuda_available(&why))
        return false;
    state.SkipWithError(("needs a CUDA GPU: " + why).c_str());
    return true;
}

std::string label(const Frame& f, bool guided)
{
    return std::to_string(f.est.width) + "x" + std::to_string(f.est.height) +
           (guided ? ", albedo + normal" : ", no guides");
}

// Args: width (1280, 1920, 3840), guides (0/1).
void BM_CudaKernel(benchmark::State& state)
{
    if (skip_without_gpu(state))
        return;
    const Frame& f = frame_of(int(state.range(0)));
    const bool guided = state.range(1) != 0;
    const DenoiseOptions options;
    const detail::FilterLayout layout =
        detail::make_filter_layout(f.est, guided ? f.guide.guides : Guides{}, options,
                                   detail::guard_levels(f.est, options), 0,
                                   detail::filter_kernel(detected_simd_level()));
    detail::CudaFilter gpu(layout, false);
    double download_ms = 0;
    for (auto _ : state) {
        gpu.run(layout, f.planes, {});
        state.SetIterationTime(gpu.timings().kernel_ms / 1000.0);
        download_ms += gpu.timings().download_ms;
    }
    state.counters["upload_ms"] = gpu.timings().upload_ms;
    state.counters["download_ms"] = download_ms / double(state.iterations());
    // Pixel-taps: every output pixel tests its disk (the layout's half widths).
    double taps = 0;
    for (int hw : layout.half_width)
        taps += 2 * hw + 1;
    state.counters["Gtaps/s"] =
        benchmark::Counter((taps - 1) * double(f.est.pixels()) * double(state.iterations()) / 1e9,
                           benchmark::Counter::kIsRate);
    state.SetLabel(label(f, guided) + ", " + cuda_device_description());
}

void BM_CudaFilter(benchmark::State& state)
{
    if (skip_without_gpu(state))
        return;
    const Frame& f = frame_of(int(state.range(0)));
    const bool guided = state.range(1) != 0;
    DenoiseOptions options;
    options.device = Device::Cuda;
    for (auto _ : state)
        filter(f.est, guided ? f.guide.guides : Guides{}, options, f.planes);
    state.SetLabel(label(f, guided) + ", end to end on planes in memory");
}

void BM_CpuFilter(benchmark::State& state)
{
    const Frame& f = frame_of(int(state.range(0)));
    const bool guided = state.range(1) != 0;
    for (auto _ : state)
        filter(f.est, guided ? f.guide.guides : Guides{}, DenoiseOptions{}, f.planes);
    state.SetLabel(label(f, guided) + ", CPU " + simd_level_name(detected_simd_level()));
}

void sizes(benchmark::internal::Benchmark* b) { b->ArgsProduct({{1280, 1920, 3840}, {0, 1}}); }

BENCHMARK(BM_CudaKernel)
    ->Apply(sizes)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly();
BENCHMARK(BM_CudaFilter)->Apply(sizes)->Apply(median_of_5);
BENCHMARK(BM_CpuFilter)->Apply(sizes)->Apply(median_of_3);

}  // namespace

BENCHMARK_MAIN();
