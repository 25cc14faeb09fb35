#include "oiiotool_commands.h"

#include <algorithm>
#include <array>

namespace statmc::tool {

bool is_oiiotool_command(std::string_view name)
{
    // From `oiiotool --help` of OpenImageIO 2.4.7.1, sorted.
    static constexpr std::array<std::string_view, 194> kCommands = {
        "--abs", "--absdiff", "--absdiffc", "--add", "--addc", "--adjust-time",
        "--attrib", "--autocc", "--autoorient", "--autopremult", "--autotile",
        "--autotrim", "--blur", "--box", "--cache", "--caption", "--capture",
        "--ccmatrix", "--ch", "--chappend", "--chnames", "--chsum", "--clamp",
        "--clear-keywords", "--colorconfig", "--colorconvert", "--colorcount",
        "--colormap", "--compression", "--contrast", "--convolve", "--create", "--crop",
        "--croptofull", "--cshift", "--cut", "--debug", "--deepen", "--deepholdout",
        "--deepmerge", "--diff", "--dilate", "--dither", "--div", "--divc",
        "--dumpdata", "--dup", "--echo", "--else", "--endfor", "--endif", "--endwhile",
        "--eraseattrib", "--erode", "--evaloff", "--evalon", "--fail", "--failpercent",
        "--fft", "--fill", "--fillholes", "--fit", "--fixnan", "--flatten", "--flip",
        "--flop", "--for", "--framepadding", "--frames", "--fullpixels", "--fullsize",
        "--hardfail", "--hardwarn", "--hash", "--help", "--iccread", "--iccwrite",
        "--iconfig", "--if", "--ifft", "--info", "--invert", "--iscolorspace",
        "--kernel", "--keyword", "--label", "--laplacian", "--line", "--list-formats",
        "--mad", "--max", "--maxc", "--maxchan", "--median", "--metamatch",
        "--metamerge", "--min", "--minc", "--minchan", "--missingfile", "--mosaic",
        "--mul", "--mulc", "--native", "--no-autopremult", "--no-clobber",
        "--no-error-exit", "--no-metamatch", "--noautocc", "--noautocrop", "--noise",
        "--nosoftwareattrib", "--ociodisplay", "--ociofiletransform", "--ociolook",
        "--oiioattrib", "--orient180", "--orientation", "--orientccw", "--orientcw",
        "--origin", "--originoffset", "--over", "--paste", "--pastemeta", "--pattern",
        "--pdiff", "--pixelaspect", "--planarconfig", "--point", "--polar", "--pop",
        "--powc", "--premult", "--printinfo", "--printstats", "--rangecheck",
        "--rangecompress", "--rangeexpand", "--reorient", "--repremult", "--resample",
        "--resize", "--rotate", "--rotate180", "--rotate270", "--rotate90",
        "--runstats", "--sansattrib", "--sattrib", "--saturate", "--scanline",
        "--selectmip", "--set", "--siappend", "--siappendall", "--sisplit",
        "--skip-bad-frames", "--st_warp", "--stats", "--sub", "--subc", "--subimage",
        "--swap", "--text", "--threads", "--tile", "--tocolorspace", "--transpose",
        "--trim", "--unmip", "--unpolar", "--unpremult", "--unsharp", "--version",
        "--views", "--warn", "--warnpercent", "--warp", "--while", "--wildcardoff",
        "--wildcardon", "--zover", "-a", "-d", "-i", "-n", "-o", "-obump", "-oenv",
        "-otex", "-q", "-u", "-v",
    };
    return std::binary_search(kCommands.begin(), kCommands.end(), name);
}

}  // namespace statmc::tool
