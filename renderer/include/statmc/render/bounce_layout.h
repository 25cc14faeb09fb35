// Which per-bounce quantities a render tracks and where each sits in a pixel's vector of
// values: B luminances L_0..L_{B−1} for ACRR (docs/method.md §7), then a light and a BSDF win
// count for each of the first M vertices for SMIS (§8). One flat index serves the
// accumulators, the batched filter, the EXR layers and the integrator's look-ups.
#pragma once

#include <algorithm>
#include <string>

namespace statmc::render {

struct BounceLayout {
    /// bounce_sample's per-sample scratch is a fixed array: more luminances are refused.
    static constexpr int kMaxLuminances = 64;

    int luminance_bounces = 0;  ///< B: L_0 (the pixel) .. L_{B−1}; 0 = not tracked
    int mis_bounces = 0;        ///< M: win counts at vertices 0..M−1; 0 = not tracked

    int quantities() const { return luminance_bounces + 2 * mis_bounces; }
    bool empty() const { return quantities() == 0; }
    bool operator==(const BounceLayout& o) const
    {
        return luminance_bounces == o.luminance_bounces && mis_bounces == o.mis_bounces;
    }
    int luminance(int j) const { return j; }
    int light_wins(int b) const { return luminance_bounces + 2 * b; }
    int bsdf_wins(int b) const { return luminance_bounces + 2 * b + 1; }
    /// The EXR AOV of quantity q (layers::bounce_aov: "bounce2L", "bounce0LightWins", ...).
    std::string aov(int q) const;
};

/// The denoised estimates of one pixel, read by the integrator during the next iteration.
/// Values are whatever the filter produced: callers must check them (NaN, negative).
struct PixelEstimates {
    const float* values = nullptr;  ///< layout.quantities() floats
    const BounceLayout* layout = nullptr;

    bool has_luminance() const { return values && layout->luminance_bounces > 0; }
    bool has_wins() const { return values && layout->mis_bounces > 0; }
    /// L̂_j, the last tracked estimate standing in for deeper vertices (§7).
    float luminance(int j) const
    {
        return values[layout->luminance(std::min(j, layout->luminance_bounces - 1))];
    }
    float light_wins(int b) const { return values[layout->light_wins(b)]; }
    float bsdf_wins(int b) const { return values[layout->bsdf_wins(b)]; }
};

}  // namespace statmc::render
