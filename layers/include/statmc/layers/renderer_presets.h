// Other renderers' channel names, mapped onto the layer contract (docs/renderers.md): a
// preset names, for each statistic and guide statmc reads, the channels a renderer writes
// for it, and what the header adds (a sample count, whether a variance is of the mean).
// Importing a file renames copies of those channels, so that everything downstream reads
// the contract alone.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc::layers {

/// The presets by name: "statmc" (the contract itself), "renderman", "pbrt-v4", "cycles".
const std::vector<std::string>& renderer_preset_names();

/// What `from=` takes: "auto" (detect_renderer), then every preset name.
const std::vector<std::string>& renderer_preset_choices();

/// What detection found: the preset ("" when none claims the image, e.g. a plain R,G,B
/// render) and the channels or attributes that gave it away.
struct RendererMatch {
    std::string preset;
    std::string evidence;
};

/// The preset whose signature `spec` carries. The contract's own (sampleCount.Y or
/// statmc:formatVersion) takes precedence; two other presets at once are a LayerError
/// naming both, never a guess.
RendererMatch detect_renderer(const OIIO::ImageSpec& spec);

/// `preset` itself for a named one; for "auto" the detected one (see detect_renderer).
/// Throws LayerError for a name that is no preset.
std::string resolve_renderer_preset(const OIIO::ImageSpec& spec, const std::string& preset);

/// An image converted to the contract, and which of its channels came from where.
struct ImportedImage {
    OIIO::ImageBuf image;
    /// (contract channel, source channel) of every renamed channel.
    std::vector<std::pair<std::string, std::string>> renamed;
};

/// The statistics `preset` maps in `src`, under the contract's names: copies of the
/// renamed channels, a constant sampleCount.Y where the renderer writes the count in the
/// header (pbrt-v4's samplesPerPixel), and statmc:variance as the renderer defines its
/// variance. Throws LayerError listing everything the preset needs and `src` lacks, and
/// for a renderer that writes no statistics at all (Cycles: the K-passes route).
ImportedImage statistics_from_preset(const OIIO::ImageBuf& src, const std::string& preset);

/// A plain render for --passes: the beauty (and alpha) and the guides `preset` maps,
/// renamed to R,G,B(,A), albedo, normal and depth; every other channel kept as it is.
/// Throws LayerError when the beauty is missing.
ImportedImage render_from_preset(const OIIO::ImageBuf& src, const std::string& preset);

/// `src` itself when it has R,G,B; else, when a renderer's preset claims it (a Cycles
/// reference, a RenderMan beauty), its beauty and guides under the contract's names in
/// `scratch`, as render_from_preset makes them. What operators that read a beauty alone
/// (compare, display) take, so that they read every renderer --denoise reads.
const OIIO::ImageBuf& contract_beauty(const OIIO::ImageBuf& src, ImportedImage& scratch);

}  // namespace statmc::layers
