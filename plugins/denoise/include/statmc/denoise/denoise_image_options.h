// What the denoise operator does with an image: the core filter's parameters plus the
// image-level choices (guides, test domain, non-finite policy).
#pragma once

#include <string>
#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/method.h"
#include "statmc/core/temporal_merge.h"
#include "statmc/layers/layer_names.h"

namespace statmc {

/// Whether a guide layer steers the filter.
enum class GuideUse {
    Auto,      ///< when the image has the layer
    Required,  ///< always; an image without the layer is an error
    Off,       ///< never
};

struct GuideSelection {
    GuideUse albedo = GuideUse::Auto;
    GuideUse normal = GuideUse::Auto;
    std::string albedo_layer = layers::kAlbedoLayer;  ///< R,G,B (or X,Y,Z) channels
    std::string normal_layer = layers::kNormalLayer;  ///< X,Y,Z (or R,G,B) channels
};

/// Which statistics the membership test compares.
enum class TestDomainChoice {
    Auto,           ///< Box-Cox when the Box-Cox layers are present, else untransformed
    BoxCox,         ///< StatMC proper; requires boxcoxMean, boxcoxVariance, boxcoxM3
    Untransformed,  ///< means and variance, as a renderer's variance AOV gives them
};

/// What NaN or Inf in the statistics means.
enum class NonfinitePolicy {
    Error,  ///< the image is refused, naming the layer and first pixel
    Zero,   ///< core's rule: the value counts as 0 and the pixel joins no test
};

/// What the denoise operator does: the product's parameters over a named method, whose
/// stages (`stages`) come with it. DenoiseImageOptions{} is the default method
/// (docs/method.md §11); of(Method::Classic) the 2024 filter with the firefly guard,
/// of(Method::Paper) the 2024 filter bit for bit.
struct DenoiseImageOptions {
    DenoiseOptions filter = method_settings(Method::Default).filter;
    GuideSelection guides;
    TestDomainChoice test = TestDomainChoice::Auto;
    NonfinitePolicy nonfinite = NonfinitePolicy::Error;
    std::string aov;  ///< the AOV denoised; "" is the beauty (R,G,B)
    /// More AOVs denoised beside `aov`, each by its own test unless `joint`.
    std::vector<std::string> aovs;
    /// With `aovs`: every listed AOV is averaged with one membership and one set of weights
    /// with `aov`, so that AOVs that sum to the beauty still sum to the denoised beauty
    /// (docs/method.md §14). That membership is decided by every listed AOV's test beside
    /// `aov`'s where they all have the test's statistics, else by `aov`'s alone (noted).
    /// The radius ladder, whose radii would differ per AOV, is then left out (noted).
    bool joint = false;
    /// Whose channel names the image has (layers/renderer_presets.h, docs/renderers.md):
    /// "auto" detects them, "statmc" is the contract itself, else a renderer's preset.
    std::string from = "auto";
    /// Also write the filter's per-pixel members and effective sample count
    /// (layers::diagnostics_channel; 0 outside the ROI). The radius ladder, whose radius
    /// differs per pixel, is then left out (noted).
    bool diagnostics = false;
    /// Frame sequences (core/temporal_merge.h, docs/method.md §13): before everything
    /// else, the members that up to `temporal.frames` frames on each side offer are merged
    /// into the frame's statistics. 0 = off; the frames come with denoise()'s neighbours.
    TemporalOptions temporal;
    /// The method's stages around the filter: set by the method, not by a parameter. A
    /// stage whose layers the image lacks is left out, and the result's
    /// statmc:denoiseSkipped attribute says which and why.
    MethodStages stages = method_settings(Method::Default).stages;

    /// The options of `method` with the product's defaults.
    static DenoiseImageOptions of(Method method);
    static DenoiseImageOptions classic() { return of(Method::Classic); }
    static DenoiseImageOptions paper() { return of(Method::Paper); }

    /// Empty when valid, else a message naming the offending parameter.
    std::string validate() const;
};

}  // namespace statmc
