// Names of the EXR layer contract (docs/exr-layers.md): channels `[<aov>.]<stat>.<channel>`
// and the namespaced header attributes. Every reader and writer takes its names from here.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace statmc::layers {

/// The contract version this build writes; it reads every version up to it. Version 2
/// added the higher moments (M3, M4, boxcoxM4); a version-1 file is a version-2 file
/// without them.
inline constexpr int kFormatVersion = 2;
/// The Box-Cox exponent the contract stores (core fixes it, see box_cox.h).
inline constexpr float kBoxCoxLambda = 0.5f;

/// Header attributes. Namespaced so that other tools carry them through untouched.
namespace attr {
inline constexpr const char* kFormatVersion = "statmc:formatVersion";  // int
inline constexpr const char* kBoxCoxLambda = "statmc:boxcoxLambda";    // float
inline constexpr const char* kVariance = "statmc:variance";            // "sample" | "mean"
inline constexpr const char* kSpp = "statmc:spp";                      // int
// When the pixels' counts differ (an interrupted render), in place of statmc:spp:
inline constexpr const char* kSppMin = "statmc:sppMin";      // int: the smallest count
inline constexpr const char* kSppMean = "statmc:sppMean";    // float: the mean count
inline constexpr const char* kSeed = "statmc:seed";          // int
inline constexpr const char* kDenoised = "statmc:denoised";  // int 1
// string: the default's stages that --denoise left out, and why (docs/exr-layers.md)
inline constexpr const char* kDenoiseSkipped = "statmc:denoiseSkipped";
// string: the layers denoise replaced, comma-separated ("beauty" for R,G,B)
inline constexpr const char* kDenoisedLayers = "statmc:denoisedLayers";
// string: how --denoise made the image, as its modifiers ("method=default:radius=8")
inline constexpr const char* kDenoiseSettings = "statmc:denoise";
// string: the statmc version that denoised it
inline constexpr const char* kVersion = "statmc:version";
// float: the share of the verified pixels whose candidate was rejected (--verify)
inline constexpr const char* kVerifyRejected = "statmc:verifyRejected";
inline constexpr const char* kRenderTime = "statmc:renderTime";  // float seconds (statmc-render)
inline constexpr const char* kScene = "statmc:scene";  // string: the scene file (statmc-render)
inline constexpr const char* kFrame =
    "statmc:frame";  // int: the frame of a sequence (statmc-render)
// Where the samples came from (sample_provenance.h): sample indices [begin, end) of every
// pixel's stream, and the farm task that drew them.
inline constexpr const char* kSampleBegin = "statmc:sampleBegin";    // int
inline constexpr const char* kSampleEnd = "statmc:sampleEnd";        // int, exclusive
inline constexpr const char* kTaskIndex = "statmc:taskIndex";        // int, 0-based
inline constexpr const char* kTaskCount = "statmc:taskCount";        // int
inline constexpr const char* kTasksMissing = "statmc:tasksMissing";  // int (merge allow_partial)
}  // namespace attr

/// Values of attr::kVariance: the per-sample variance s² (default) or the variance of the
/// mean s²/n, as RenderMan's `mse` stores it.
inline constexpr const char* kVarianceOfSample = "sample";
inline constexpr const char* kVarianceOfMean = "mean";

/// The statistics stored per AOV and colour channel. From Moment3 on (format version 2,
/// optional): the higher central moments per sample, M3/n and M4/n of the untransformed
/// samples and M4/n of the Box-Cox ones.
enum class Statistic {
    Mean,
    Variance,
    BoxCoxMean,
    BoxCoxVariance,
    BoxCoxMoment3,
    Moment3,
    Moment4,
    BoxCoxMoment4
};

/// All statistics in storage order, for loops over layers.
const std::vector<Statistic>& all_statistics();

/// The one sample count of a pixel, shared by every AOV of the image.
inline constexpr const char* kSampleCountLayer = "sampleCount";
inline constexpr const char* kSampleCountChannel = "sampleCount.Y";

/// Default guide layers.
inline constexpr const char* kAlbedoLayer = "albedo";  // albedo.R/G/B
inline constexpr const char* kNormalLayer = "normal";  // normal.X/Y/Z
inline constexpr const char* kDepthLayer = "depth";    // depth.Z
/// Screen-space motion to the previous frame in pixels, at the first hit (motion.X/Y):
/// what temporal denoising follows from frame to frame (docs/exr-layers.md).
inline constexpr const char* kMotionLayer = "motion";

/// What `--denoise:diagnostics=1` adds under `[<aov>.]diagnostics` (FilterDiagnostics):
/// per pixel, the filter's members (the centre included) and its effective sample count
/// (Σ W)² / Σ W²/n_j.
inline constexpr const char* kDiagnosticsLayer = "diagnostics";
inline constexpr const char* kMembersChannel = "members";
inline constexpr const char* kEffectiveSamplesChannel = "effectiveSamples";
/// What --verify adds under `[<aov>.]diagnostics`: where the candidate was rejected.
inline constexpr const char* kRejectedChannel = "rejected";

/// "diagnostics.members", "diffuse.diagnostics.effectiveSamples", ...
std::string diagnostics_channel(std::string_view aov, std::string_view quantity);

/// The layer that holds `stat` of `aov` ("" is the beauty): the mean is the AOV itself
/// ("" for the beauty, whose channels are unprefixed), the others are "variance",
/// "diffuse.variance", "bounce1.boxcoxM3" and so on.
std::string statistic_layer(std::string_view aov, Statistic stat);

/// Per-bounce quantities a renderer tracks for its own sampling decisions (docs/method.md §7,
/// §8), each stored as a one-channel (Y) AOV of its own beside the beauty.
enum class BounceQuantity {
    Luminance,  ///< L_j: luminance of the radiance from path vertex j on, throughput 1 (ACRR)
    LightWins,  ///< wins of light sampling at vertex j (SMIS)
    BsdfWins,   ///< wins of BSDF sampling at vertex j (SMIS)
};

/// The AOV of `quantity` at path vertex `bounce` (0 = the first hit): "bounce2L",
/// "bounce0LightWins", "bounce0BsdfWins". One name part, so that its statistics stay
/// within two levels ("bounce2L.boxcoxM3.Y"), and no leading digit.
std::string bounce_aov(BounceQuantity quantity, int bounce);

/// Whether `aov` can prefix channel names: not empty, no dot or space, no leading digit.
bool is_valid_aov_name(std::string_view aov);

/// The short name of a statistic: "mean", "variance", "boxcoxMean", ...
const char* statistic_name(Statistic stat);

/// Whether `channel` holds a statistic other than the mean of `aov` ("variance.R",
/// "boxcoxM3.B", ...) or the sample count: what a plain render never has.
bool is_statistics_channel(std::string_view channel, std::string_view aov = "");

/// Whether `channel` holds a statistic of any AOV other than its mean ("variance.R",
/// "diffuse.boxcoxM3.B", "bounce1L.M4.Y"), the sample count, the sub-pixel moments or the
/// guides' variances ("albedoVariance.Y"): what a compositor has no use for once the image
/// is denoised.
bool is_any_statistics_channel(std::string_view channel);

/// The layer holding a guide layer's variance: "albedo" → "albedoVariance" (channel .Y).
std::string guide_variance_layer(std::string_view guide_layer);

/// `layer.suffix`, or the bare suffix for the unprefixed layer "".
std::string channel_name(std::string_view layer, std::string_view suffix);

/// Channel suffixes: colour R,G,B; scalar Y; vector X,Y,Z; depth Z.
const std::vector<std::string>& colour_suffixes();
const std::vector<std::string>& scalar_suffixes();
const std::vector<std::string>& vector_suffixes();

/// The suffixes a quantity of `channels` channels is stored under (1 → Y, 3 → R,G,B).
/// Throws LayerError for other counts: the contract names no other layout.
const std::vector<std::string>& suffixes_for_channels(int channels);

}  // namespace statmc::layers
