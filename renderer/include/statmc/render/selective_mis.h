// How the two direct-lighting techniques are weighted: standard MIS (the power heuristic)
// or selective MIS (SMIS, docs/method.md §8), which skips a technique that has (almost) never
// won at this pixel and vertex and gives the other one weight 1.
//
// Unbiasedness. The choice is made per pixel and vertex from the estimates of earlier
// iterations and holds for the whole iteration: it never depends on the current sample.
// §8's "and that has not won in this sample" would re-enable a technique mid-sample,
// depending on the sample itself, which is biased; we do not do it. Skipping BSDF
// sampling (light weight 1) needs light sampling to reach every emitter point the BSDF
// could: it does for our area lights (triangles by area, spheres by the visible cone).
// Skipping light sampling (BSDF weight 1) needs the BSDF sample to cover its lobe: it
// does for matte and microfacet metal. Specular vertices never light-sample and are left
// alone, and there are no delta lights (which would always have to be light-sampled).
// At most one technique is ever skipped.
//
// Win rates. A "win rate" here is a technique's share of the wins at that vertex,
// η_T = wins_T / (wins_light + wins_bsdf), from the denoised win counts. Absolute rates per
// camera sample would skip both techniques in dim pixels whose paths rarely reach a light;
// the share cannot, and it is undefined (standard MIS) where nothing was ever won.
#pragma once

namespace statmc::render {

enum class MisMode { Standard, Selective };

struct MisSettings {
    MisMode mode = MisMode::Standard;
    int tracked_bounces = 6;   ///< vertices 0..M−1 get win counts and SMIS
    float threshold = 0.001f;  ///< skip a technique whose win share is below this, in [0, 0.5)
};

/// The power heuristic (β = 2) weight of a strategy with density `pdf_a` against `pdf_b`.
inline float power_heuristic(float pdf_a, float pdf_b)
{
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0 ? a / (a + b) : 0.f;
}

/// Which techniques run at one vertex.
struct TechniqueChoice {
    bool light = true;
    bool bsdf = true;

    /// The weight of a light sample (light_pdf, bsdf_pdf as solid-angle densities).
    float light_weight(float light_pdf, float bsdf_pdf) const
    {
        return bsdf ? power_heuristic(light_pdf, bsdf_pdf) : 1.f;
    }
    /// The weight of a BSDF-sampled emitter hit.
    float bsdf_weight(float bsdf_pdf, float light_pdf) const
    {
        if (!bsdf)
            return 0.f;
        return light ? power_heuristic(bsdf_pdf, light_pdf) : 1.f;
    }
};

/// SMIS's choice from the denoised win counts of one pixel and vertex: standard (both)
/// unless both counts are finite and ≥ 0 with a positive sum, and then a technique is
/// skipped when its share is below `threshold` (< 0.5, so never both).
TechniqueChoice choose_techniques(float light_wins, float bsdf_wins, float threshold);

}  // namespace statmc::render
