// What the denoise operator does with an image: the core filter's parameters plus the
// image-level choices (guides, test domain, non-finite policy).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "statmc/core/denoise_options.h"
#include "statmc/core/radius_ladder.h"
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

/// Whose test decides the one membership of joint AOVs (docs/method.md §14).
enum class JointTest {
    Auto,  ///< All when `aov` and every listed AOV have the test's statistics, else Lead
    All,   ///< a neighbour joins where the tests of `aov` and of every listed AOV accept it
    Lead,  ///< `aov`'s test alone (the beauty's by default); the AOVs need only their means
};

/// What NaN or Inf in the statistics means.
enum class NonfinitePolicy {
    Error,  ///< the image is refused, naming the layer and first pixel
    Zero,   ///< core's rule: the value counts as 0 and the pixel joins no test
};

/// The default (DenoiseImageOptions{}) is the measured one (docs/method.md §11): the 2024
/// filter with the firefly guard, each pixel at its own radius by the ICI ladder, whose
/// intervals read moderated variances. classic() is the default before the ladder,
/// paper() the 2024 filter bit for bit.
struct DenoiseImageOptions {
    DenoiseOptions filter;
    GuideSelection guides;
    TestDomainChoice test = TestDomainChoice::Auto;
    NonfinitePolicy nonfinite = NonfinitePolicy::Error;
    std::string aov;  ///< the AOV denoised; "" is the beauty (R,G,B)
    /// More AOVs denoised beside `aov`, each by its own test unless `joint`.
    std::vector<std::string> aovs;
    /// With `aovs`: every listed AOV is averaged with the members and weights of `aov`'s
    /// test (the beauty's by default) rather than its own, so that AOVs that sum to the
    /// beauty still sum to the denoised beauty (docs/method.md §14). The radius ladder,
    /// whose radii would differ per AOV, is then left out (noted, as for a missing layer).
    bool joint = false;
    JointTest joint_test = JointTest::Auto;
    /// Whose channel names the image has (layers/renderer_presets.h, docs/renderers.md):
    /// "auto" detects them, "statmc" is the contract itself, else a renderer's preset.
    std::string from = "auto";
    /// Also write the filter's per-pixel members and effective sample count
    /// (layers::diagnostics_channel; 0 outside the ROI).
    bool diagnostics = false;
    /// 0: off (the 2024 filter). Else the Box-Cox variances are first denoised over this
    /// radius (core/variance_filter.h, docs/method.md §10) and the mean test reads them;
    /// needs the Box-Cox test and the boxcoxM4 layer (format version 2). Experimental:
    /// off by default until the evaluation has measured it on rendered frames.
    int variance_radius = 0;
    /// 0: off. Else the do-no-harm guard at this significance (core/harm_guard.h,
    /// docs/method.md §11): each output value is pulled back into its own pixel's
    /// confidence interval; needs the untransformed variance with M3 and M4 (format
    /// version 2). Experimental, off by default until the evaluation has measured it.
    double harm_alpha = 0;
    /// 0: off. Else each pixel takes its own radius from 0 and the rungs of ici_radii
    /// (up to filter.radius) by the intersection of confidence intervals at this
    /// significance (core/radius_ladder.h, docs/method.md §11); needs the untransformed
    /// variance with M3 and M4. Cannot be combined with diagnostics yet.
    double ici_alpha = 0.005;
    /// With the ladder: a pixel goes on up the ladder where all of its 8-neighbours do,
    /// even when its own intervals would stop it (RadiusLadderOptions::overrule_lone_stops).
    bool ici_neighbours = true;
    /// With the ladder: its rungs, ascending, each in [1, 100]; those at or above
    /// filter.radius are dropped, and filter.radius is always the last rung
    /// (RadiusLadderOptions::radii). Fewer rungs cost less: each is a pass over the image.
    std::vector<int> ici_radii = RadiusLadderOptions{}.radii;
    /// 0: off. Else, before every other stage, the part of each pixel's variance that a
    /// linear gradient across the pixel explains is removed where the regression is
    /// significant at this level (core/explained_variance.h, docs/method.md §12); needs
    /// the subpixel and covU/covV layers (statmc-render writes them). Experimental.
    double explained_alpha = 0;
    /// The prior degrees of freedom with which every variance filter above (variance_radius,
    /// do_no_harm, ici) moderates a pixel's variance towards its neighbourhood's
    /// (VarianceFilterOptions::prior_dof, docs/method.md §10); 0 = off.
    double variance_prior_dof = 16;
    /// Which neighbours lend their variance to that prior: those whose mean the t-test at
    /// this significance cannot tell from the pixel's (VarianceFilterOptions::prior_alpha,
    /// docs/method.md §10); 0 = every neighbour.
    double variance_prior_alpha = 0.05;
    /// Whether every variance filter above first averages the s² of the neighbours whose
    /// intervals on ln σ² agree (VarianceFilterOptions::interval_test, StatER's variance
    /// denoising) or leaves each pixel's own s² to the moderation alone: the default method
    /// measured the same either way and takes the cheaper (docs/method.md §10).
    bool variance_test = false;
    /// 0: off. Else a neighbour joins only where the means over the boxes of this radius
    /// around the two pixels pass the t-test too (core/context_channel.h, docs/method.md §5):
    /// a pixel on a light's edge is then not averaged with the surface beside it. Skipped,
    /// with a note, for joint_test=all and layers of four channels.
    int context_radius = 1;
    /// true: a stage whose layers the image lacks (the ladder on a format-1 file without
    /// M3/M4) or that the request excludes (the ladder with diagnostics) is skipped, and the
    /// result's statmc:denoiseSkipped attribute says which and why. false: either is an
    /// error. The presets keep it true; a stage asked for by name sets it false.
    bool optional_stages = true;
    /// Frame sequences (core/temporal_merge.h, docs/method.md §13): before everything
    /// else, the members that up to `temporal.frames` frames on each side offer are merged
    /// into the frame's statistics. 0 = off; the frames come with denoise()'s neighbours.
    TemporalOptions temporal;

    /// The default before the radius ladder: the 2024 filter with the firefly guard.
    static DenoiseImageOptions classic();
    /// The 2024 filter exactly (DenoiseOptions::paper()), no further stage.
    static DenoiseImageOptions paper();

    /// Empty when valid, else a message naming the offending parameter.
    std::string validate() const;
};

/// Radii as a parameter spells them: "1,2,3,5,8,12,20" ("" for none).
std::string radii_text(const std::vector<int>& radii);
/// The radii that text spells, or nullopt where an item is not a whole number.
std::optional<std::vector<int>> radii_from_text(const std::string& text);

}  // namespace statmc
