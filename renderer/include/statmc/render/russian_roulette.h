// Russian roulette: classic (pbrt-v3, from the path throughput alone) and
// approximate-contribution RR (ACRR, docs/method.md §7), which compares the throughput times
// the denoised radiance expected from the next vertex with the pixel's denoised value.
//
// Unbiasedness: a path survives with probability p ∈ (0, 1] and its throughput is divided
// by p. As written in §7, ACRR terminates with q = max(0.05, 1 − s), so q = 1 (p = 0) when
// s = 0, i.e. wherever the denoised estimate L̂_{b+1} is 0 — and a zero estimate does not
// mean a zero truth (a light not yet found from this pixel). Such paths would be lost, a
// bias. We therefore clamp p ≥ kMinSurvival (weights ≤ 1/kMinSurvival = 20).
#pragma once

#include <optional>

#include "statmc/render/vec.h"

namespace statmc::render {

enum class RouletteMode { Classic, Acrr };

struct RouletteSettings {
    RouletteMode mode = RouletteMode::Classic;
    /// Roulette after the BSDF sample at vertices b ≥ start_bounce (0 = the first hit).
    /// 4 is pbrt-v3's `bounces > 3`; the seed's C.2 experiments start at 0.
    int start_bounce = 4;
    /// ACRR: tracked bounces beside the pixel (B = tracked_bounces + 1 luminances).
    int tracked_bounces = 4;
};

/// The smallest survival probability ACRR gives (see the file comment).
inline constexpr float kMinSurvival = 0.05f;

/// pbrt-v3 (path.cpp, rrThreshold 1): while max β < 1, terminate with q = max(0.05, 1 − max β),
/// so p = 1 − q = min(max β, 0.95); at max β ≥ 1 the path always survives (p = 1). β is the
/// throughput with refraction's radiance scaling factored out (pbrt-v3's rrBeta).
float classic_survival(const Rgb& beta);

/// ACRR's survival probability after sampling the BSDF at a vertex: s = max β · L̂_next /
/// L̂_0 (L̂_next the estimate for the vertex the new ray leads to); p = 1 when s ≥ 1, else
/// min(s, 0.95) clamped to ≥ kMinSurvival. Empty — fall back to classic — when the
/// estimates are unusable: L̂_0 not finite or ≤ 0, L̂_next not finite or < 0.
std::optional<float> acrr_survival(float beta_max, float next_estimate, float pixel_estimate);

}  // namespace statmc::render
