#include "tile_pass.h"

#include <algorithm>

#include <pmmintrin.h>
#include <x86intrin.h>
#include <xmmintrin.h>

#include <tbb/parallel_for.h>

#include "statmc/render/sampler.h"

namespace statmc::render::detail {

namespace {

// One sample's motion to the previous frame: where the previous camera saw the sample's
// first hit (a miss: a point far along the ray, i.e. the direction), minus where the sample
// is now. A point behind the previous camera has no defined motion and adds 0.
void add_motion(Film& film, std::size_t pixel, std::size_t npix, const Camera& previous,
                const Ray& ray, const GuideSample& guide, float x, float y)
{
    const Vec3 p = guide.hit ? guide.first_hit : ray.origin + ray.direction * 1e7f;
    float px = 0, py = 0;
    if (!previous.raster(p, px, py))
        return;
    film.motion_sum[pixel] += double(px) - x;
    film.motion_sum[npix + pixel] += double(py) - y;
}

// Flush-to-zero and denormals-are-zero for the scope's lifetime; the caller's mode after.
class FlushDenormals {
public:
    FlushDenormals() : saved_(_mm_getcsr())
    {
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
    }
    ~FlushDenormals() { _mm_setcsr(saved_); }
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

private:
    unsigned int saved_;
};

}  // namespace

PassCounts render_pass(const TilePass& pass, std::uint64_t first, int spp,
                       const std::vector<std::uint32_t>* counts, const std::atomic<bool>* cancel,
                       bool skippable)
{
    constexpr int kTile = 16;
    const RenderSettings& settings = pass.settings;
    Film& film = pass.film;
    const int tiles_x = (settings.width + kTile - 1) / kTile,
              tiles_y = (settings.height + kTile - 1) / kTile;
    const std::size_t npix = std::size_t(settings.width) * settings.height;
    std::atomic<std::uint64_t> samples{0}, cycles{0}, bounce_cycles{0};
    tbb::parallel_for(0, tiles_x * tiles_y, [&](int tile) {
        if (skippable && cancel && cancel->load())
            return;
        const std::uint64_t t0 = __rdtsc();
        // Denormals flushed on every worker, so no pixel depends on the thread it ran on;
        // and only here, so that what runs after the render (the output, a merge, the
        // estimates' filter) never depends on which threads rendered tiles.
        const FlushDenormals flush;
        const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
        const int x1 = std::min(x0 + kTile, settings.width),
                  y1 = std::min(y0 + kTile, settings.height);
        PathRecord record;
        const bool records = film.steering || film.bounces;
        // With --bounce-layers and both roulette and MIS steered, the layers' quantities
        // are steering's: computed once for both.
        const bool shared_values =
            film.steering && film.bounces && film.steering->layout() == film.bounces->layout();
        std::vector<float> steering_values(
            film.steering ? std::size_t(film.steering->layout().quantities()) : 0);
        std::vector<float> bounce_values(
            film.bounces && !shared_values ? std::size_t(film.bounces->layout().quantities()) : 0);
        std::uint64_t n = 0, bounce_cycles_local = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                const std::size_t pixel = std::size_t(y) * settings.width + x;
                // PixelEstimates{} steers nothing, as no estimates would.
                const PixelEstimates pixel_estimates =
                    pass.estimates ? pass.estimates->pixel(pixel) : PixelEstimates{};
                const int take = counts ? int((*counts)[pixel]) : spp;
                const std::uint64_t begin = counts ? std::uint64_t(film.stats.at(x, y).n) : first;
                n += std::uint64_t(take);
                for (int s = 0; s < take; ++s) {
                    Sampler sampler(settings.seed, pixel,
                                    settings.first_sample + begin + std::uint64_t(s));
                    const float jx = sampler.get1d(), jy = sampler.get1d();
                    const Ray ray = pass.camera.generate(float(x) + jx, float(y) + jy);
                    GuideSample guide;
                    const Rgb L = pass.integrator.radiance(
                        ray, sampler, guide, records ? &record : nullptr, &pixel_estimates);
                    const float value[3] = {L.r, L.g, L.b};
                    film.stats.add(x, y, value);
                    if (records) {
                        const std::uint64_t b0 = pass.profiling ? __rdtsc() : 0;
                        if (film.steering) {
                            bounce_sample(record, film.steering->layout(), steering_values.data());
                            film.steering->add(x, y, steering_values.data());
                        }
                        if (film.bounces && shared_values) {
                            film.bounces->add(x, y, steering_values.data());
                        } else if (film.bounces) {
                            bounce_sample(record, film.bounces->layout(), bounce_values.data());
                            film.bounces->add(x, y, bounce_values.data());
                        }
                        if (pass.profiling)
                            bounce_cycles_local += __rdtsc() - b0;
                    }
                    double albedo_square = 0, normal_square = 0;
                    for (int c = 0; c < 3; ++c) {
                        film.albedo_sum[c * npix + pixel] += guide.albedo[c];
                        film.normal_sum[c * npix + pixel] += guide.normal[c];
                        albedo_square += double(guide.albedo[c]) * guide.albedo[c];
                        normal_square += double(guide.normal[c]) * guide.normal[c];
                    }
                    film.albedo_squares[pixel] += albedo_square;
                    film.normal_squares[pixel] += normal_square;
                    film.depth_sum[pixel] += guide.depth;
                    if (!film.motion_sum.empty())
                        add_motion(film, pixel, npix, *settings.previous_camera, ray, guide,
                                   float(x) + jx, float(y) + jy);
                }
            }
        samples += n;
        cycles += __rdtsc() - t0;
        bounce_cycles += bounce_cycles_local;
        pass.progress.advance(n);
    });
    return {samples.load(), cycles.load(), bounce_cycles.load()};
}

}  // namespace statmc::render::detail
