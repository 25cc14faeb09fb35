// The image files the CLI tests feed statmc, written fresh into each test's directory.
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace statmc::test {

inline constexpr int kCliWidth = 24, kCliHeight = 16;

/// Full statistics (Box-Cox included) with albedo and normal guides.
OIIO::ImageBuf cli_statistics_image();
/// Mean + variance + sampleCount only: a renderer's variance AOV.
OIIO::ImageBuf cli_variance_aov_image();
/// Plain render k of a frame (R,G,B,A and albedo), different noise per k.
OIIO::ImageBuf cli_render(int k, int width = kCliWidth, int height = kCliHeight);

/// Every channel of `want` is in `got` under its name, bit for bit (gtest failures).
void expect_same_channels(const OIIO::ImageBuf& got, const OIIO::ImageBuf& want);

}  // namespace statmc::test
