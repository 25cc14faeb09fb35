#include "statmc/core/radius_ladder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "filter_layout.h"
#include "statmc/core/critical_values.h"
#include "statmc/core/thread_limit.h"
#include "window_sums.h"

namespace statmc {

namespace {

std::vector<int> rungs(const RadiusLadderOptions& ladder, int radius)
{
    std::vector<int> r;
    for (int v : ladder.radii)
        if (v > 0 && v < radius && (r.empty() || v > r.back()))
            r.push_back(v);
    if (radius > 0)
        r.push_back(radius);
    return r;
}

// Rung 0, then one walk of the largest disk, each rung adding its annulus and deciding
// which pixels go on (docs/method.md §11). `walked`: empty, or the pixels each rung computes.
void walk_rungs(const StatisticsView& stats, const EstimatorImage& est, const Guides& guides,
                const DenoiseOptions& options, const std::vector<Plane>& out,
                const RadiusLadderOptions& ladder, const std::vector<int>& radii,
                const std::vector<PixelMask>& walked, int nthreads)
{
    const int w = est.width, h = est.height, channels = stats.channels;
    const std::size_t pixels = est.pixels();
    static const PixelMask kEvery;
    const PixelMask& near = walked.empty() ? kEvery : walked.front();
    const std::vector<float> variance = denoise_variances(
        stats, TestDomain::Untransformed, guides, ladder.variance, nthreads, SimdLevel::Auto, near);
    const double z = normal_critical_value(ladder.alpha);

    // Rung 0: the pixel's own mean and its interval. `lo`/`hi` hold the running
    // intersection; `open` says the pixel may still take a larger radius.
    std::vector<double> lo(pixels * channels), hi(pixels * channels);
    std::vector<char> open(pixels, 1);
    auto half_width = [&](std::size_t k, double samples) {
        return samples > 0 ? z * std::sqrt(std::max(double(variance[k]), 0.0) / samples) : 0.0;
    };
    // Pixels are independent: rows run in parallel, with the same result for any count.
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const double n = est.count[i];
                open[i] = n >= 2 && (near.empty() || near[i]);
                for (int c = 0; c < channels; ++c) {
                    const std::size_t k = c * pixels + i;
                    const double v = est.value[k];
                    out[c](x, y) = float(v);
                    lo[k] = v - half_width(k, n);
                    hi[k] = v + half_width(k, n);
                }
            }
        });
    });

    std::vector<float> rung_out(pixels * channels), effective(pixels);
    std::vector<Plane> rung_planes;
    for (int c = 0; c < channels; ++c)
        rung_planes.push_back(dense_plane(rung_out.data() + c * pixels, w));
    FilterDiagnostics diagnostics;
    diagnostics.effective_samples = dense_plane(effective.data(), w);
    // Per rung: whether the pixel's own intervals let it go on (1), or not (0, and for
    // pixels already stopped).
    std::vector<char> overlaps(pixels);
    auto all_neighbours_overlap = [&](int x, int y) {
        for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
            for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx)
                if ((xx != x || yy != y) && !overlaps[std::size_t(yy) * w + xx])
                    return false;
        return w * h > 1;
    };
    // Takes the rung's value, `hw` each channel's half width at this rung; `restart`: its
    // interval becomes the intersection.
    auto go_on = [&](int x, int y, const double* hw, bool restart) {
        const std::size_t i = std::size_t(y) * w + x;
        for (int c = 0; c < channels; ++c) {
            const std::size_t k = c * pixels + i;
            const double v = rung_out[k];
            lo[k] = restart ? v - hw[c] : std::max(lo[k], v - hw[c]);
            hi[k] = restart ? v + hw[c] : std::min(hi[k], v + hw[c]);
            out[c](x, y) = rung_out[k];
        }
    };
    // One walk of the largest disk: each rung adds its annulus to the one before.
    auto take_rung = [&](int) {
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                bool own = open[i] != 0;
                double hw[4];
                for (int c = 0; c < channels && own; ++c) {
                    const std::size_t k = c * pixels + i;
                    const double v = rung_out[k];
                    hw[c] = half_width(k, effective[i]);
                    own = std::max(lo[k], v - hw[c]) <= std::min(hi[k], v + hw[c]);
                }
                overlaps[i] = own;
                if (own)
                    go_on(x, y, hw, false);
            }
        });
        // The pixels that their own intervals stop (a few per cent): a lone stop among
        // neighbours that all go on is overruled, its intersection (now empty) restarting
        // from this rung's interval; any other stop stands, with the previous rung's value.
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                if (!open[i] || overlaps[i])
                    continue;
                if (ladder.overrule_lone_stops && all_neighbours_overlap(x, y)) {
                    double hw[4];
                    for (int c = 0; c < channels; ++c)
                        hw[c] = half_width(c * pixels + i, effective[i]);
                    go_on(x, y, hw, true);
                } else {
                    open[i] = 0;
                }
            }
        });
    };
    detail::filter_rungs(est, guides, options, radii, rung_planes, diagnostics, nthreads,
                         SimdLevel::Auto, take_rung, walked);
}

}  // namespace

void filter_with_radius_ladder(const StatisticsView& stats, const EstimatorImage& est,
                               const Guides& guides, const DenoiseOptions& options,
                               const std::vector<Plane>& out, const RadiusLadderOptions& ladder,
                               int nthreads, const PixelMask& wanted)
{
    if (!(ladder.alpha > 0 && ladder.alpha < 1))
        throw std::invalid_argument("radius ladder: alpha must be in (0, 1)");
    if (est.channels < 1 || est.channels > 4)
        throw std::invalid_argument("radius ladder: takes 1 to 4 channels, as the filter does");
    if (int(out.size()) < stats.channels)
        throw std::invalid_argument("radius ladder: fewer output planes than channels");
    if (stats.width != est.width || stats.height != est.height || stats.channels > est.channels)
        throw std::invalid_argument("radius ladder: statistics and estimators differ in shape");
    require_mask_fits(wanted, est.width, est.height);
    const int w = est.width, h = est.height;
    const std::vector<int> radii = rungs(ladder, options.radius);
    // The checks read the ladder's output within their reach of a wanted pixel.
    PixelMask checked;
    if (!wanted.empty() && checks_reach(ladder) > 0)
        run_with_threads(nthreads,
                         [&] { checked = grown_mask(wanted, w, h, checks_reach(ladder)); });
    const PixelMask& target = checked.empty() ? wanted : checked;
    // A pixel's state after rung k depends on its own after rung k − 1 and on its
    // 8-neighbours' rung-k values and states after rung k − 1 (the lone-stop rule). So of K
    // rungs, rung k is walked for the pixels within K − k + 1 of a wanted one, and the
    // first rung and the intervals cover those within K.
    std::vector<PixelMask> walked(target.empty() ? 0 : radii.size());
    if (!target.empty())
        run_with_threads(nthreads, [&] {
            for (std::size_t k = radii.size(); k-- > 0;)
                walked[k] = grown_mask(k + 1 < radii.size() ? walked[k + 1] : target, w, h, 1);
        });
    walk_rungs(stats, est, guides, options, out, ladder, radii, walked, nthreads);
    // The checks read the statistics channel by channel: from dense copies, not from the
    // image's interleaved records (the same values). The walk's buffers are gone by now.
    std::vector<float> storage;
    StatisticsView inputs = stats;
    if (checks_reach(ladder) > 0)
        run_with_threads(nthreads, [&] { inputs = detail::dense_check_inputs(stats, storage); });
    keep_window_energy(inputs, out, ladder.energy, nthreads);
    keep_window_residual(inputs, out, ladder.residual, nthreads);
}

}  // namespace statmc
