// What --info, --stats and --diff print, line for line as oiiotool 2.4 prints it, so
// that scripts reading oiiotool's reports can read statmc's.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "image_stack.h"

namespace statmc::tool {

/// The headers of the file an image was read from, per subimage: the pixel types it stores
/// (layers::read_image_headers). Empty: the images' own.
using FileSpecs = std::vector<OIIO::ImageSpec>;

/// `label : W x H, C channel, type format`, then with `verbose` the channel list, the
/// windows when they differ and every attribute; with `all_subimages` each subimage.
void print_info(std::ostream& out, const StackImage& image, const FileSpecs& file_specs,
                bool verbose, bool all_subimages);

/// The "Stats Min/Max/Avg/StdDev/NanCount/InfCount/FiniteCount", "Constant" and
/// "Monochrome" lines of subimage 0, or with `all_subimages` of each under a heading.
void print_all_stats(std::ostream& out, const StackImage& image, const FileSpecs& file_specs,
                     bool all_subimages, int nthreads);

/// Compares `a` with `b` (thresholds as oiiotool's defaults); prints the report and
/// returns whether it passed.
bool print_diff(std::ostream& out, const StackImage& a, const StackImage& b, int nthreads);

}  // namespace statmc::tool
