// The denoise operator end to end on an in-memory image, file I/O left out: what
// `statmc in.exr --denoise` adds to reading and writing the frame (it runs in place), and
// the stages it spends that on besides the filter (bench_filter). 1280×720 RGB, Box-Cox statistics,
// n = 64, r = 20; medians over 5 repetitions.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <OpenImageIO/imagebuf.h>

#include "bench_frame.h"
#include "bench_timing.h"
#include "statmc/core/energy_check.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/residual_check.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/exr_files.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/layers/statistics_validation.h"

namespace {

using namespace statmc;

// The frame under the EXR layer contract, with albedo and normal layers; with
// $STATMC_BENCH_FRAME, that statistics EXR instead (a render, so that another denoiser can
// be timed on the same frame: scripts/speed_vs_oidn.sh).
const OIIO::ImageBuf& image()
{
    static const bench::GuidePlanes guides;
    static const OIIO::ImageBuf buf = [] {
        if (const char* path = std::getenv("STATMC_BENCH_FRAME"); path && *path) {
            OIIO::ImageBuf file = layers::read_image_file(path);
            return file;
        }
        layers::GuidePlanes planes;
        planes.albedo = guides.guides.albedo;
        planes.normal = guides.guides.normal;
        return layers::make_statistics_image(bench::frame(), {}, planes);
    }();
    return buf;
}

// range(2): 0 the classic filter (the default before the radius ladder), 1 the default.
DenoiseImageOptions method(std::int64_t which)
{
    return which ? DenoiseImageOptions{} : DenoiseImageOptions::classic();
}

const char* method_label(std::int64_t which) { return which ? "default" : "classic"; }

void BM_DenoiseOperator(benchmark::State& state)
{
    DenoiseImageOptions opt = method(state.range(2));
    const GuideUse use = state.range(1) ? GuideUse::Required : GuideUse::Off;
    opt.guides.albedo = opt.guides.normal = use;
    const OIIO::ImageBuf& in = image();  // built before the clock starts
    OIIO::ImageBuf out;
    for (auto _ : state) {
        if (!denoise(out, in, opt, {}, int(state.range(0))))
            state.SkipWithError(out.geterror().c_str());
        benchmark::DoNotOptimize(out.localpixels());
    }
    state.SetLabel(std::string(method_label(state.range(2))) +
                   (state.range(1) ? ", albedo + normal guides" : ", no guides"));
}

// dst = src, as statmc's command line runs it: the means are patched into the input.
void BM_DenoiseOperatorInPlace(benchmark::State& state)
{
    DenoiseImageOptions opt = method(state.range(2));
    const GuideUse use = state.range(1) ? GuideUse::Required : GuideUse::Off;
    opt.guides.albedo = opt.guides.normal = use;
    const OIIO::ImageBuf& in = image();
    for (auto _ : state) {
        state.PauseTiming();
        OIIO::ImageBuf buf = in.copy(OIIO::TypeDesc::FLOAT);
        state.ResumeTiming();
        if (!denoise(buf, buf, opt, {}, int(state.range(0))))
            state.SkipWithError(buf.geterror().c_str());
        benchmark::DoNotOptimize(buf.localpixels());
    }
    state.SetLabel(
        std::string(method_label(state.range(2))) +
        (state.range(1) ? ", in place, albedo + normal guides" : ", in place, no guides"));
}

// Frame t of a static shot with its neighbours t−2 … t+2 (other seeds), built once.
struct Shot {
    std::vector<OIIO::ImageBuf> frames;
    Shot()
    {
        static const bench::GuidePlanes guides;
        layers::GuidePlanes planes;
        planes.albedo = guides.guides.albedo;
        planes.normal = guides.guides.normal;
        for (std::uint64_t seed = 2; seed <= 5; ++seed)
            frames.push_back(
                layers::make_statistics_image(bench::make_frame(false, seed), {}, planes));
    }
    FrameNeighbours around(int reach) const
    {
        FrameNeighbours n;
        for (int k = 0; k < reach; ++k) {
            n.previous.push_back(&frames[std::size_t(2 * k)]);
            n.next.push_back(&frames[std::size_t(2 * k + 1)]);
        }
        return n;
    }
};

// Temporal denoising (temporal = K) against K = 0, the per-frame cost; the default method,
// albedo + normal guides, all cores. What the tool adds besides is reading the neighbours.
void BM_DenoiseTemporal(benchmark::State& state)
{
    static const Shot shot;
    DenoiseImageOptions opt = method(state.range(1));
    opt.guides.albedo = opt.guides.normal = GuideUse::Required;
    opt.temporal.frames = int(state.range(0));
    const FrameNeighbours neighbours = shot.around(opt.temporal.frames);
    OIIO::ImageBuf out;
    for (auto _ : state) {
        if (!denoise(out, image(), neighbours, opt))
            state.SkipWithError(out.geterror().c_str());
        benchmark::DoNotOptimize(out.localpixels());
    }
    state.SetLabel(std::string(method_label(state.range(1))) + ", temporal " +
                   std::to_string(opt.temporal.frames));
}

// The stages outside the filter, on all cores.
void BM_StageValidate(benchmark::State& state)
{
    const OIIO::ImageBuf& in = image();
    const layers::StatisticsChannels ch = layers::find_statistics(in.spec());
    for (auto _ : state)
        benchmark::DoNotOptimize(layers::validate_statistics(in, ch));
}

void BM_StageEstimators(benchmark::State& state)
{
    const StatisticsView view = layers::read_statistics(image());
    for (auto _ : state)
        benchmark::DoNotOptimize(estimators_from_statistics(view, TestDomain::BoxCox));
}

// The default's two window checks (radius 3, as the method runs them) on an output that is
// the noisy means dimmed by 10% in every tenth row, so that both find windows off. They
// read the image's own interleaved planes here; the ladder hands them dense copies.
void BM_StageWindowChecks(benchmark::State& state)
{
    const StatisticsView view = layers::read_statistics(image());
    const int w = view.width, h = view.height;
    std::vector<float> base(std::size_t(w) * h * view.channels), planes_data(base.size());
    for (int c = 0; c < view.channels; ++c)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                base[(std::size_t(c) * h + y) * w + x] =
                    view.mean[c](x, y) * (y % 10 == 0 ? 0.9f : 1.0f);
    std::vector<Plane> out;
    for (int c = 0; c < view.channels; ++c)
        out.push_back(dense_plane(planes_data.data() + std::size_t(c) * w * h, w));
    for (auto _ : state) {
        state.PauseTiming();
        planes_data = base;
        state.ResumeTiming();
        keep_window_energy(view, out, {3, 0.005});
        keep_window_residual(view, out, {3, 0.005});
        benchmark::DoNotOptimize(planes_data.data());
    }
}

void BM_StageCopy(benchmark::State& state)
{
    const OIIO::ImageBuf& in = image();
    for (auto _ : state) {
        OIIO::ImageBuf copy = in.copy(OIIO::TypeDesc::FLOAT);
        benchmark::DoNotOptimize(copy.localpixels());
    }
}

// Args: threads (0 = all cores), guides (0/1), method (0 classic, 1 default).
BENCHMARK(BM_DenoiseOperator)
    ->Args({0, 0, 0})
    ->Args({0, 1, 0})
    ->Args({1, 0, 0})
    ->Args({0, 0, 1})
    ->Args({0, 1, 1})
    ->Apply(median_of_5);
BENCHMARK(BM_DenoiseOperatorInPlace)
    ->Args({0, 0, 0})
    ->Args({0, 1, 0})
    ->Args({0, 0, 1})
    ->Args({0, 1, 1})
    ->Apply(median_of_5);
// Args: temporal K, method (0 classic, 1 default).
BENCHMARK(BM_DenoiseTemporal)
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({0, 0})
    ->Args({2, 0})
    ->Apply(median_of_5);
BENCHMARK(BM_StageValidate)->Apply(median_of_5);
BENCHMARK(BM_StageEstimators)->Apply(median_of_5);
BENCHMARK(BM_StageWindowChecks)->Apply(median_of_5);
BENCHMARK(BM_StageCopy)->Apply(median_of_5);

}  // namespace

BENCHMARK_MAIN();
