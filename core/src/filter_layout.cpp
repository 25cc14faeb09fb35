#include "filter_layout.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <new>
#include <vector>

#include <sys/mman.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/firefly_guard.h"

namespace statmc::detail {

namespace {

constexpr float kNever = -std::numeric_limits<float>::infinity();
constexpr double kLog2e = 1.4426950408889634;
// Scaled guides are clamped to this: squared differences of six of them stay finite, so
// a guide weight is never exp2(−∞ + ∞) = NaN.
constexpr float kGuideBound = 1e17f;

float finite_or_zero(float v) { return std::isfinite(v) ? v : 0.f; }

// u of the pixel (filter_layout.h): Σ scale² · s²/n over the guides with a variance; 0 where
// the count or a variance is not a positive finite number, bounded like the guides.
float guide_noise_of(const std::vector<std::pair<ConstPlane, float>>& variances, int x, int y,
                     double n)
{
    if (!(n > 0) || !std::isfinite(n))
        return 0.f;
    double u = 0;
    for (const auto& [plane, scale2] : variances) {
        const float v = plane(x, y);
        if (v > 0 && std::isfinite(v))
            u += double(scale2) * v / n;
    }
    return float(std::min(u, double(kGuideBound)));
}

// The disk at radius r: row dy's half width, −1 where the row is outside it.
int disk_half_width(const FilterLayout& L, int r, int dy)
{
    if (std::abs(dy) > r)
        return -1;
    const int hw = int(std::floor(std::sqrt(std::max(0.0, double(r) * r - double(dy) * dy))));
    return std::min(hw, L.pad_x);
}

void build_window(FilterLayout& L, const DenoiseOptions& options)
{
    const double inv_two_sigma2 =
        1.0 / (2.0 * double(options.sigma_spatial) * options.sigma_spatial);
    const int cols = 2 * L.pad_x + 1;
    set_window(L, options.radius, 0);
    L.spatial_weight.assign(std::size_t(cols) * (2 * L.pad_y + 1), 0.f);
    L.spatial_log2_weight.assign(L.spatial_weight.size(), kNever);
    for (int dy = -L.pad_y; dy <= L.pad_y; ++dy)
        for (int dx = -L.half_width[dy + L.pad_y]; dx <= L.half_width[dy + L.pad_y]; ++dx) {
            const double log_w = -(double(dx) * dx + double(dy) * dy) * inv_two_sigma2;
            L.spatial_log2_weight[L.table_index(dx, dy)] = float(log_w * kLog2e);
            L.spatial_weight[L.table_index(dx, dy)] = float(std::exp(log_w));
        }
}

constexpr std::size_t kHugePage = std::size_t(2) << 20;

/// Uninitialised floats for the padded planes. Large blocks are aligned to 2 MiB and
/// marked for transparent huge pages: a fresh 50 MB block otherwise takes ~13000 page
/// faults, a fifth of the filter's time on a small radius.
float* page_memory(std::size_t floats)
{
    const std::size_t bytes = (floats * sizeof(float) + kHugePage - 1) / kHugePage * kHugePage;
    void* p = std::aligned_alloc(kHugePage, bytes);
    if (!p)
        throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(p, bytes, MADV_HUGEPAGE);  // advice only: without THP it is ignored
#endif
    return static_cast<float*>(p);
}

/// Marks the chunks where the guard may refuse a pair: some window pixel's level above
/// some centre's limit, or some centre's own level (the mutual half) above some window
/// pixel's mutual limit.
/// The window's extremes are bounded through those of 16×16 blocks: coarse, so it marks a
/// little more than needed, and one pass over the levels.
void mark_guarded_chunks(FilterLayout& L, const NoiseLevels& noise)
{
    L.chunks = (L.width + L.lanes - 1) / L.lanes;
    L.guarded.assign(std::size_t(L.chunks) * L.height, 0);
    constexpr float kAny = std::numeric_limits<float>::infinity();
    if (std::all_of(noise.limit.begin(), noise.limit.end(), [](float l) { return l == kAny; }))
        return;
    constexpr int kBlock = 16;
    const int bw = (L.width + kBlock - 1) / kBlock, bh = (L.height + kBlock - 1) / kBlock;
    std::vector<float> block_max(std::size_t(bw) * bh, 0.f), block_min(block_max.size(), kAny);
    tbb::parallel_for(0, bh, [&](int by) {
        float* row_max = block_max.data() + std::size_t(by) * bw;
        float* row_min = block_min.data() + std::size_t(by) * bw;
        for (int y = by * kBlock; y < std::min(L.height, (by + 1) * kBlock); ++y)
            for (int x = 0; x < L.width; ++x) {
                const std::size_t i = std::size_t(y) * L.width + x;
                row_max[x / kBlock] = std::max(row_max[x / kBlock], noise.level[i]);
                row_min[x / kBlock] = std::min(row_min[x / kBlock], noise.mutual_limit[i]);
            }
    });
    tbb::parallel_for(
        tbb::blocked_range<int>(0, L.height, 16), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y < rows.end(); ++y)
                for (int k = 0; k < L.chunks; ++k) {
                    const int x0 = k * L.lanes, x1 = std::min(L.width, x0 + L.lanes) - 1;
                    float least = kAny, loudest = 0;
                    for (int x = x0; x <= x1; ++x) {
                        least = std::min(least, noise.limit[std::size_t(y) * L.width + x]);
                        loudest = std::max(loudest, noise.own[std::size_t(y) * L.width + x]);
                    }
                    float most = 0, window_least = kAny;
                    for (int by = std::max(0, (y - L.pad_y) / kBlock);
                         by <= std::min(bh - 1, (y + L.pad_y) / kBlock); ++by)
                        for (int bx = std::max(0, (x0 - L.pad_x) / kBlock);
                             bx <= std::min(bw - 1, (x1 + L.pad_x) / kBlock); ++bx) {
                            most = std::max(most, block_max[std::size_t(by) * bw + bx]);
                            window_least =
                                std::min(window_least, block_min[std::size_t(by) * bw + bx]);
                        }
                    L.guarded[std::size_t(y) * L.chunks + k] =
                        most > least || loudest > window_least;
                }
        });
}

}  // namespace

void FilterLayout::Release::operator()(float* p) const { std::free(p); }

void set_window(FilterLayout& L, int outer, int inner)
{
    L.reach_y = std::min(outer, L.pad_y);
    L.half_width.resize(2 * L.pad_y + 1);
    L.inner_half_width.resize(2 * L.pad_y + 1);
    for (int dy = -L.pad_y; dy <= L.pad_y; ++dy) {
        L.half_width[dy + L.pad_y] = disk_half_width(L, outer, dy);
        L.inner_half_width[dy + L.pad_y] = disk_half_width(L, inner, dy);
    }
}

void set_wanted(FilterLayout& L, const PixelMask& mask)
{
    require_mask_fits(mask, L.width, L.height);
    L.wanted.clear();
    if (mask.empty())
        return;
    L.wanted.assign(std::size_t(L.chunks) * L.height, 0);
    tbb::parallel_for(0, L.height, [&](int y) {
        const std::uint8_t* row = mask.data() + std::size_t(y) * L.width;
        for (int x = 0; x < L.width; ++x)
            if (row[x])
                L.wanted[std::size_t(y) * L.chunks + x / L.lanes] = 1;
    });
}

NoiseLevels guard_levels(const EstimatorImage& est, const DenoiseOptions& options)
{
    return firefly_guard_applies(est, options.firefly_ratio)
               ? noise_levels(est, options.firefly_ratio)
               : NoiseLevels{};
}

FilterLayout make_filter_layout(const EstimatorImage& est, const Guides& guides,
                                const DenoiseOptions& options, const NoiseLevels& noise,
                                int nthreads, const FilterKernel& kernel, bool with_inverse_count)
{
    FilterLayout L;
    L.width = est.width;
    L.height = est.height;
    L.channels = est.channels;
    L.averaged = est.channels - est.context_channels;
    L.lanes = kernel.lanes;
    // No neighbour lies further than the image extends; clamping keeps padding small
    // for a radius larger than the image.
    L.pad_x = std::min(options.radius, est.width - 1);
    L.pad_y = std::min(options.radius, est.height - 1);
    // Room for the last SIMD chunk of a row to read past the width.
    constexpr int kMaxLanes = 16;
    const int padded_width = est.width + 2 * L.pad_x + kMaxLanes;
    L.stride = padded_width;
    L.plane_size = std::size_t(padded_width) * (est.height + 2 * L.pad_y);

    // plane, √(log2 e)/(√2·σ): the guide term of the weight becomes 2^−Σ(Δg)², whose
    // power of two the kernels apply without a range reduction by ln 2.
    std::vector<std::pair<ConstPlane, float>> guide_planes;
    auto guide_scale = [](float sigma) { return float(std::sqrt(kLog2e / 2.0) / sigma); };
    if (guides.has_albedo())
        for (const ConstPlane& p : guides.albedo)
            guide_planes.emplace_back(p, guide_scale(options.sigma_albedo));
    if (guides.has_normal())
        for (const ConstPlane& p : guides.normal)
            guide_planes.emplace_back(p, guide_scale(options.sigma_normal));
    L.guide_count = int(guide_planes.size());
    // Each guide's per-sample variance with its scale², when the image has it and the
    // option is on: u = Σ scale² · s²/n (guide_noise_of).
    std::vector<std::pair<ConstPlane, float>> guide_variances;
    auto add_variance = [&](const ConstPlane& v, float sigma) {
        const float scale = guide_scale(sigma);
        if (v && options.guide_noise)
            guide_variances.emplace_back(v, scale * scale);
    };
    if (guides.has_albedo())
        add_variance(guides.albedo_variance, options.sigma_albedo);
    if (guides.has_normal())
        add_variance(guides.normal_variance, options.sigma_normal);

    // The guard's planes exist only where some chunk needs them.
    mark_guarded_chunks(L, noise);
    const bool guard = std::find(L.guarded.begin(), L.guarded.end(), 1) != L.guarded.end();
    // Only guides with their variances get the plane (and the kernel's noise loop).
    const int noise_planes = guide_variances.empty() ? 0 : 1;
    const int planes = 3 * L.channels + L.guide_count + noise_planes + (guard ? 4 : 0) +
                       (with_inverse_count ? 1 : 0);
    // Not zeroed: every float, padding included, is written once below, by the thread
    // that will mostly read it (zeroing 50 MB first cost as much as filling it).
    L.storage_floats = L.plane_size * planes;
    L.storage = std::unique_ptr<float[], FilterLayout::Release>(page_memory(L.storage_floats));
    const std::ptrdiff_t origin = std::ptrdiff_t(L.pad_y) * L.stride + L.pad_x;
    auto plane_origin = [&](int k) { return L.storage.get() + k * L.plane_size + origin; };
    float* mean[kMaxEstimatorChannels];
    float* threshold[kMaxEstimatorChannels];
    float* value[kMaxEstimatorChannels];
    for (int c = 0; c < L.channels; ++c) {
        mean[c] = plane_origin(c);
        threshold[c] = plane_origin(L.channels + c);
        value[c] = plane_origin(2 * L.channels + c);
        L.mean[c] = mean[c];
        L.threshold[c] = threshold[c];
        L.value[c] = value[c];
    }
    float* guide[6];
    for (int g = 0; g < L.guide_count; ++g) {
        guide[g] = plane_origin(3 * L.channels + g);
        L.guide[g] = guide[g];
    }
    const int first_after_guides = 3 * L.channels + L.guide_count + noise_planes;
    float* guide_noise = noise_planes ? plane_origin(3 * L.channels + L.guide_count) : nullptr;
    L.guide_noise = guide_noise;
    float* noise_level = guard ? plane_origin(first_after_guides) : nullptr;
    float* noise_limit = guard ? plane_origin(first_after_guides + 1) : nullptr;
    float* noise_own = guard ? plane_origin(first_after_guides + 2) : nullptr;
    float* noise_mutual = guard ? plane_origin(first_after_guides + 3) : nullptr;
    L.noise_own = noise_own;
    L.noise_mutual = noise_mutual;
    L.noise = noise_level;
    L.noise_limit = noise_limit;
    float* inverse_count =
        with_inverse_count ? plane_origin(first_after_guides + (guard ? 4 : 0)) : nullptr;
    L.inverse_count = inverse_count;

    const float max_count = tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, est.pixels(), 1 << 16), 0.f,
        [&](const tbb::blocked_range<std::size_t>& r, float m) {
            for (std::size_t i = r.begin(); i < r.end(); ++i)
                m = std::max(m, std::isfinite(est.count[i]) ? est.count[i] : 0.f);
            return m;
        },
        [](float a, float b) { return std::max(a, b); });
    const auto table = CriticalValues::shared(options.alpha, 2.0 * std::floor(max_count) - 2.0);
    const CriticalValues& critical = *table;

    // What a padded pixel holds: never a member (T = −∞), everything else 0.
    auto pad = [&](std::ptrdiff_t p, int x0, int x1) {
        for (int c = 0; c < L.channels; ++c) {
            std::fill(mean[c] + p + x0, mean[c] + p + x1, 0.f);
            std::fill(threshold[c] + p + x0, threshold[c] + p + x1, kNever);
            std::fill(value[c] + p + x0, value[c] + p + x1, 0.f);
        }
        for (int g = 0; g < L.guide_count; ++g)
            std::fill(guide[g] + p + x0, guide[g] + p + x1, 0.f);
        if (guide_noise)
            std::fill(guide_noise + p + x0, guide_noise + p + x1, 0.f);
        if (guard) {
            std::fill(noise_level + p + x0, noise_level + p + x1, 0.f);
            std::fill(noise_limit + p + x0, noise_limit + p + x1, 0.f);
            std::fill(noise_own + p + x0, noise_own + p + x1, 0.f);
            std::fill(noise_mutual + p + x0, noise_mutual + p + x1, 0.f);
        }
        if (inverse_count)
            std::fill(inverse_count + p + x0, inverse_count + p + x1, 0.f);
    };
    const int row_end = L.stride - L.pad_x;  // one past the last padded column, from x = 0
    auto fill_rows = [&](const tbb::blocked_range<int>& rows) {
        double last_count = -1, last_gamma2 = 0;  // counts repeat: spare the table lookup
        std::vector<std::uint8_t> testable(est.width);
        std::vector<double> gamma2(est.width);
        for (int y = rows.begin(); y < rows.end(); ++y) {
            const std::ptrdiff_t row = std::ptrdiff_t(y) * L.stride;
            if (y < 0 || y >= est.height) {
                pad(row, -L.pad_x, row_end);
                continue;
            }
            pad(row, -L.pad_x, 0);
            pad(row, est.width, row_end);
            // The row plane by plane, so that the channels' loops vectorise.
            est.testable_row(y, testable.data());
            const float* count = est.count.data() + est.index(0, 0, y);
            for (int x = 0; x < est.width; ++x) {
                const double n = count[x];
                if (testable[x] && n != last_count) {
                    // The fast form tests each side at df = 2n − 2 (docs/method.md §4).
                    const double gamma = critical.gamma(2.0 * std::floor(n) - 2.0);
                    last_count = n;
                    last_gamma2 = gamma * gamma;
                }
                gamma2[x] = last_gamma2;
            }
            for (int c = 0; c < L.channels; ++c) {
                const std::size_t i = est.index(c, 0, y);
                const float *in_value = est.value.data() + i, *in_mean = est.test_mean.data() + i,
                            *in_variance = est.test_variance.data() + i;
                float *out_value = value[c] + row, *out_mean = mean[c] + row,
                      *out_threshold = threshold[c] + row;
                for (int x = 0; x < est.width; ++x) {
                    out_value[x] = in_value[x];
                    out_mean[x] = testable[x] ? in_mean[x] : 0.f;
                    out_threshold[x] =
                        testable[x] ? float(std::min(gamma2[x] * in_variance[x], double(FLT_MAX)))
                                    : kNever;
                }
            }
            for (int x = 0; x < est.width; ++x) {
                const std::ptrdiff_t p = row + x;
                const double n = count[x];
                for (int g = 0; g < L.guide_count; ++g)
                    guide[g][p] = std::clamp(finite_or_zero(guide_planes[g].first(x, y)) *
                                                 guide_planes[g].second,
                                             -kGuideBound, kGuideBound);
                if (guide_noise)
                    guide_noise[p] = guide_noise_of(guide_variances, x, y, n);
                if (guard) {
                    noise_level[p] = noise.level[std::size_t(y) * est.width + x];
                    noise_limit[p] = noise.limit[std::size_t(y) * est.width + x];
                    noise_own[p] = noise.own[std::size_t(y) * est.width + x];
                    noise_mutual[p] = noise.mutual_limit[std::size_t(y) * est.width + x];
                }
                if (inverse_count) {
                    const float count_or_zero = finite_or_zero(float(n));
                    inverse_count[p] = count_or_zero > 0 ? 1.f / count_or_zero : 0.f;
                }
            }
        }
    };
    const tbb::blocked_range<int> padded_rows(-L.pad_y, est.height + L.pad_y, 16);
    if (nthreads == 1)
        fill_rows(padded_rows);
    else
        tbb::parallel_for(padded_rows, fill_rows);

    build_window(L, options);
    L.flat_guide_weight.resize(L.spatial_log2_weight.size());
    kernel.exp2(L.spatial_log2_weight.data(), L.flat_guide_weight.data(),
                L.flat_guide_weight.size());
    return L;
}

}  // namespace statmc::detail
