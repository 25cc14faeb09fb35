// Synthetic statistics images for tests: samples with known distributions accumulated
// with core's own accumulators, written under the layer contract, and the results the
// core filter gives on them directly (the expectation the operators must reproduce).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "same_bits.h"
#include "statmc/core/denoise_options.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/statistics_image.h"
#include "statmc/layers/guide_layers.h"

namespace statmc::test {

/// Statistics of a noisy frame: a dark left half and a bright right half (an edge the
/// test must keep), exponentially distributed samples (skewed, as path tracing gives),
/// and spp + (x + y) % 3 samples per pixel so that degrees of freedom differ.
StatisticsPlanes noisy_statistics(int width, int height, int spp, std::uint32_t seed);

/// `stats` as another renderer's variance AOV holds it: mean, variance and count only (no
/// Box-Cox set, no higher moments).
StatisticsPlanes variance_aov(StatisticsPlanes stats);

/// Dense guide data (albedo following the edge, normals tilting with y, depth) and its
/// planes.
struct GuideData {
    int width = 0;
    std::vector<float> albedo, normal, depth;  // channel-major
    layers::GuidePlanes planes() const;
};
GuideData make_guides(int width, int height, std::uint32_t seed);

/// What core's filter makes of `stats` (or a window of it): dense, channel-major. With
/// `context` > 0, over the estimators with the green (or only) channel's context of that
/// radius (context_channel.h), as the denoise operator's default tests them.
std::vector<float> core_filtered(const StatisticsView& stats, TestDomain domain,
                                 const Guides& guides, const DenoiseOptions& options,
                                 int context = 0);

/// Channel `name` of `buf` at image coordinates (x, y); fails the test when absent.
float channel_value(const OIIO::ImageBuf& buf, const std::string& name, int x, int y);

/// `buf` without the named channels; or with layer `from_layer` renamed `to_layer`.
OIIO::ImageBuf without_channels(const OIIO::ImageBuf& buf, const std::vector<std::string>& names);
OIIO::ImageBuf renamed_channels(const OIIO::ImageBuf& buf, const std::string& from_layer,
                                const std::string& to_layer);
/// `buf` with the layers of sub-pixel position moments that statmc-render wrote before
/// format version 3 (subpixel, covU, covV, boxcoxCovU, boxcoxCovV), holding values no
/// statistic could (a negative subpixel.UU): what an older file carries.
OIIO::ImageBuf with_retired_position_layers(const OIIO::ImageBuf& buf);
/// `buf` with its channels in reverse order.
OIIO::ImageBuf reversed_channels(const OIIO::ImageBuf& buf);

/// Sets channel `name` at (x, y) of a local float image.
void set_channel(OIIO::ImageBuf& buf, const std::string& name, int x, int y, float value);

/// Writes `buf` as EXR (throws on failure) and reads a file back as local float pixels.
void write_exr(const OIIO::ImageBuf& buf, const std::string& path);
OIIO::ImageBuf read_exr(const std::string& path);

}  // namespace statmc::test
