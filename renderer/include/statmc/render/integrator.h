// Unidirectional path tracing with next-event estimation, both strategies combined by
// the power heuristic (light sampling at each non-specular vertex, BSDF sampling that
// happens to hit an emitter) or selectively (SMIS, docs/method.md §8), and Russian roulette,
// classic or approximate-contribution (ACRR, §7). The per-pixel estimates that ACRR and
// SMIS steer by come from earlier iterations (PixelEstimates); without them both behave
// classically.
#pragma once

#include <vector>

#include "statmc/render/bounce_layout.h"
#include "statmc/render/russian_roulette.h"
#include "statmc/render/sampler.h"
#include "statmc/render/scene.h"
#include "statmc/render/selective_mis.h"

namespace statmc::render {

/// The feature guides of one camera sample (docs/method.md §5): albedo and shading normal at
/// the first non-specular vertex (albedo through any specular chain before it), and the
/// distance to the first hit. All zero when the ray escapes.
struct GuideSample {
    Rgb albedo;
    Vec3 normal;
    float depth = 0;
    Vec3 first_hit;  ///< where the camera ray first hits, when `hit`
    bool hit = false;
};

/// What one camera path did, vertex by vertex, for the per-bounce statistics of ACRR
/// (docs/method.md §7: L_j = the radiance arriving at vertex j with throughput 1 from there on,
/// i.e. Σ of contributions at vertices ≥ j divided by the throughput at vertex j) and
/// the technique win counts of SMIS (§8, from the MIS weights). Filled only when a
/// recorder is passed; the integrator's result does not depend on it.
struct PathRecord {
    enum class Technique { Emission, Light, Bsdf };
    struct Contribution {
        int bounce;           ///< the vertex whose lighting this is (0 = first hit)
        Technique technique;  ///< Emission: seen directly (camera or specular chain)
        float mis_weight;     ///< the power-heuristic weight (what standard MIS uses and
                              ///< what decides a win, even where SMIS used 1 or 0); 1 for Emission
        Rgb value;            ///< added to the pixel sample

        /// The vertex at which the value was added: a BSDF-sampled hit lights the previous
        /// vertex but is found, with the throughput of, the next one.
        int arrival() const { return technique == Technique::Bsdf ? bounce + 1 : bounce; }
    };
    std::vector<Rgb> throughput;  ///< β on arrival at vertex b (β_0 = 1), roulette weights included
    /// Π 1/p of the roulette survived before vertex b (1 at vertex 0): how much more
    /// likely reaching b would have been without roulette.
    std::vector<float> roulette_weight;
    std::vector<Contribution> contributions;

    void clear()
    {
        throughput.clear();
        roulette_weight.clear();
        contributions.clear();
    }
};

struct IntegratorSettings {
    int maxdepth = 5;  ///< pbrt's meaning: 1 = direct lighting only
    RouletteSettings roulette;
    MisSettings mis;
};

class PathIntegrator {
public:
    PathIntegrator(const Scene& scene, IntegratorSettings settings)
        : scene_(scene), settings_(settings)
    {
    }

    /// The radiance arriving along `ray` (one Monte Carlo sample). `estimates` (of the
    /// pixel, from earlier iterations) steer ACRR and SMIS when the settings ask for them;
    /// null, or unusable values, mean classic roulette and standard MIS.
    Rgb radiance(const Ray& ray, Sampler& sampler, GuideSample& guide, PathRecord* record = nullptr,
                 const PixelEstimates* estimates = nullptr) const;

private:
    /// `rr_beta` is β with refraction's radiance scaling factored out (classic roulette's).
    float survival(int bounce, const Rgb& beta, const Rgb& rr_beta,
                   const PixelEstimates* estimates) const;
    TechniqueChoice techniques(int bounce, const PixelEstimates* estimates) const;

    const Scene& scene_;
    IntegratorSettings settings_;
};

}  // namespace statmc::render
