// Unidirectional path tracing with next-event estimation, both strategies combined by
// the power heuristic (light sampling at each non-specular vertex, BSDF sampling that
// happens to hit an emitter), and classic Russian roulette after a few bounces.
//
// Written to grow: the per-vertex steps (emission, light sampling, continuation) are
// separate so that per-bounce statistics (ACRR, method.md §7) and selective MIS (§8) can
// hook into PathState without restructuring the loop.
#pragma once

#include <vector>

#include "sampler.h"
#include "scene.h"

namespace statmc::render {

/// The feature guides of one camera sample (method.md §5): albedo and shading normal at
/// the first non-specular vertex (albedo through any specular chain before it), and the
/// distance to the first hit. All zero when the ray escapes.
struct GuideSample {
    Rgb albedo;
    Vec3 normal;
    float depth = 0;
};

/// What one camera path did, vertex by vertex, for the per-bounce statistics of ACRR
/// (method.md §7: L_j = the radiance arriving at vertex j with throughput 1 from there on,
/// i.e. Σ of contributions at vertices ≥ j divided by the throughput at vertex j) and
/// the technique win counts of SMIS (§8, from the MIS weights). Filled only when a
/// recorder is passed; the integrator's result does not depend on it.
struct PathRecord {
    enum class Technique { Emission, Light, Bsdf };
    struct Contribution {
        int bounce;           ///< the vertex whose lighting this is (0 = first hit)
        Technique technique;  ///< Emission: seen directly (camera or specular chain)
        float mis_weight;     ///< 1 for Emission
        Rgb value;            ///< added to the pixel sample
    };
    std::vector<Rgb> throughput;  ///< β on arrival at vertex b (β_0 = 1)
    std::vector<Contribution> contributions;

    void clear()
    {
        throughput.clear();
        contributions.clear();
    }
};

struct IntegratorSettings {
    int maxdepth = 5;         ///< pbrt's meaning: 1 = direct lighting only
    int rr_start_bounce = 3;  ///< classic roulette from the bounce after this one (pbrt: > 3)
};

class PathIntegrator {
public:
    PathIntegrator(const Scene& scene, IntegratorSettings settings) : scene_(scene), settings_(settings) {}

    /// The radiance arriving along `ray` (one Monte Carlo sample).
    Rgb radiance(const Ray& ray, Sampler& sampler, GuideSample& guide, PathRecord* record = nullptr) const;

private:
    const Scene& scene_;
    IntegratorSettings settings_;
};

/// The power heuristic (β = 2) weight of a strategy with density `pdf_a` against `pdf_b`.
inline float power_heuristic(float pdf_a, float pdf_b)
{
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.f;
}

}  // namespace statmc::render
