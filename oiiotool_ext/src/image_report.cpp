#include "image_report.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/strutil.h>

#include "statmc/layers/layer_error.h"
#include "statmc/layers/renderer_presets.h"

namespace statmc::tool {

namespace {

// oiiotool 2.4 counts both warnings and failures against 1e-6.
constexpr float kDiffThreshold = 1e-6f;

// The format the file stores (the stack holds float pixels; reports show the file's): its
// header as read, else what the ImageBuf knows.
const OIIO::ImageSpec& file_spec(const StackImage& image, const FileSpecs& file_specs,
                                 std::size_t s)
{
    return s < file_specs.size() ? file_specs[s] : image.subimages[s].nativespec();
}

// A file with per-channel types shows them all: "half/float/float".
std::string type_text(const OIIO::ImageSpec& spec)
{
    if (spec.channelformats.empty())
        return spec.format.c_str();
    std::string text;
    for (int c = 0; c < spec.nchannels; ++c)
        text += (c ? "/" : "") + std::string(spec.channelformat(c).c_str());
    return text;
}

std::string summary(const OIIO::ImageBuf& image, const OIIO::ImageSpec& spec)
{
    const std::string format = image.file_format_name().empty()
                                   ? std::string("openexr")
                                   : std::string(image.file_format_name());
    return OIIO::Strutil::sprintf("%4d x %4d, %d channel, %s %s", spec.width, spec.height,
                                  spec.nchannels, type_text(spec).c_str(), format.c_str());
}

// oiiotool's order: plain names first, then namespaced ones, case-insensitively.
bool attribute_before(const OIIO::ParamValue* a, const OIIO::ParamValue* b)
{
    const std::string na = a->name().string(), nb = b->name().string();
    const bool ca = na.find(':') != std::string::npos, cb = nb.find(':') != std::string::npos;
    if (ca != cb)
        return !ca;
    return OIIO::Strutil::iless(na, nb);
}

// statmc's one addition to oiiotool's report, for another renderer's file only (statmc's
// own files and plain renders read exactly as oiiotool prints them): the preset that
// --denoise and --passes take with from=auto, and why (docs/renderers.md).
void print_renderer_preset(std::ostream& out, const OIIO::ImageSpec& spec)
{
    try {
        const layers::RendererMatch match = layers::detect_renderer(spec);
        if (!match.preset.empty() && match.preset != "statmc")
            out << "    statmc preset: " << match.preset << " (" << match.evidence << ")\n";
    } catch (const layers::LayerError& e) {
        out << "    statmc preset: none; " << e.what() << "\n";
    }
}

void print_details(std::ostream& out, const OIIO::ImageBuf& image, const OIIO::ImageSpec& native)
{
    const OIIO::ImageSpec& spec = image.spec();
    out << "    channel list: ";
    for (int c = 0; c < spec.nchannels; ++c) {
        out << (c ? ", " : "") << spec.channelnames[c];
        if (!native.channelformats.empty())
            out << " (" << native.channelformat(c) << ")";
    }
    out << "\n";
    if (spec.x || spec.y || spec.z)
        out << "    pixel data origin: x=" << spec.x << ", y=" << spec.y << "\n";
    if (spec.full_width != spec.width || spec.full_height != spec.height)
        out << "    full/display size: " << spec.full_width << " x " << spec.full_height << "\n";
    if (spec.full_x != spec.x || spec.full_y != spec.y)
        out << "    full/display origin: " << spec.full_x << ", " << spec.full_y << "\n";
    print_renderer_preset(out, spec);
    std::vector<const OIIO::ParamValue*> attributes;
    for (const OIIO::ParamValue& p : spec.extra_attribs)
        attributes.push_back(&p);
    std::stable_sort(attributes.begin(), attributes.end(), attribute_before);
    // Strings are printed raw, as oiiotool does (metadata_val would escape new lines).
    for (const OIIO::ParamValue* p : attributes)
        out << "    " << p->name() << ": "
            << (p->type() == OIIO::TypeString ? "\"" + p->get_string() + "\""
                                              : spec.metadata_val(*p, true))
            << "\n";
}

char format_letter(OIIO::TypeDesc t)
{
    return t == OIIO::TypeDesc::HALF ? 'h' : t == OIIO::TypeDesc::FLOAT ? 'f' : 'u';
}

void print_subimage_sizes(std::ostream& out, const StackImage& image, const FileSpecs& file_specs)
{
    out << "    " << image.subimages.size() << " subimages: ";
    for (std::size_t s = 0; s < image.subimages.size(); ++s) {
        const OIIO::ImageSpec& spec = file_spec(image, file_specs, s);
        out << (s ? ", " : "") << spec.width << "x" << spec.height << " [";
        for (int c = 0; c < spec.nchannels; ++c)
            out << (c ? "," : "") << format_letter(spec.channelformat(c));
        out << "]";
    }
    out << "\n";
}

std::string values_at(const OIIO::ImageBuf& image, int x, int y, int z)
{
    std::ostringstream os;
    for (int c = 0; c < image.nchannels(); ++c)
        os << (c ? ", " : "") << image.getchannel(x, y, z, c);
    return os.str();
}

std::string percent(std::size_t count, const OIIO::ImageBuf& image)
{
    std::ostringstream os;
    os.precision(3);
    os << 100.0 * double(count) / double(image.spec().image_pixels());
    return os.str();
}

std::string subimage_heading(const StackImage& image, const FileSpecs& file_specs, std::size_t s)
{
    return OIIO::Strutil::sprintf(" subimage %2zu: ", s) +
           summary(image.subimages[s], file_spec(image, file_specs, s)) + "\n";
}

void print_stats(std::ostream& out, const OIIO::ImageBuf& image, int nthreads)
{
    const auto stats = OIIO::ImageBufAlgo::computePixelStats(image, OIIO::ROI(), nthreads);
    auto floats = [&](const char* what, const std::vector<float>& values) {
        out << "    Stats " << what << ":";
        for (float v : values)
            out << OIIO::Strutil::sprintf(" %f", v);
        out << " (float)\n";
    };
    auto counts = [&](const char* what, const std::vector<OIIO::imagesize_t>& values) {
        out << "    Stats " << what << ": ";
        for (OIIO::imagesize_t v : values)
            out << v << " ";
        out << "\n";
    };
    floats("Min", stats.min);
    floats("Max", stats.max);
    floats("Avg", stats.avg);
    floats("StdDev", stats.stddev);
    counts("NanCount", stats.nancount);
    counts("InfCount", stats.infcount);
    counts("FiniteCount", stats.finitecount);
    std::vector<float> constant(image.nchannels());
    if (OIIO::ImageBufAlgo::isConstantColor(image, 0.0f, constant, OIIO::ROI(), nthreads)) {
        out << "    Constant: Yes\n    Constant Color:";
        for (float v : constant)
            out << OIIO::Strutil::sprintf(" %f", v);
        out << " (float)\n";
    } else {
        out << "    Constant: No\n";
    }
    out << "    Monochrome: "
        << (OIIO::ImageBufAlgo::isMonochrome(image, 0.0f, OIIO::ROI(), nthreads) ? "Yes" : "No")
        << "\n";
}

}  // namespace

void print_info(std::ostream& out, const StackImage& image, const FileSpecs& file_specs,
                bool verbose, bool all_subimages)
{
    const bool several = image.subimages.size() > 1;
    out << OIIO::Strutil::sprintf("%-20s : ", image.label)
        << summary(image.image(), file_spec(image, file_specs, 0))
        << (several && !verbose ? OIIO::Strutil::sprintf(" (%zu subimages)", image.subimages.size())
                                : "")
        << "\n";
    if (!verbose)
        return;
    if (several)
        print_subimage_sizes(out, image, file_specs);
    if (!all_subimages || !several) {
        print_details(out, image.image(), file_spec(image, file_specs, 0));
        return;
    }
    for (std::size_t s = 0; s < image.subimages.size(); ++s) {
        out << subimage_heading(image, file_specs, s);
        print_details(out, image.subimages[s], file_spec(image, file_specs, s));
    }
}

void print_all_stats(std::ostream& out, const StackImage& image, const FileSpecs& file_specs,
                     bool all_subimages, int nthreads)
{
    if (!all_subimages || image.subimages.size() == 1) {
        print_stats(out, image.image(), nthreads);
        return;
    }
    for (std::size_t s = 0; s < image.subimages.size(); ++s) {
        out << subimage_heading(image, file_specs, s);
        print_stats(out, image.subimages[s], nthreads);
    }
}

bool print_diff(std::ostream& out, const StackImage& a, const StackImage& b, int nthreads)
{
    const OIIO::ImageBuf &A = a.image(), &B = b.image();
    const auto cr =
        OIIO::ImageBufAlgo::compare(A, B, kDiffThreshold, kDiffThreshold, OIIO::ROI(), nthreads);
    out << "Computing diff of \"" << a.label << "\" vs \"" << b.label << "\"\n";
    if (cr.nwarn || cr.nfail) {
        out << "  Mean error = " << cr.meanerror << "\n"
            << "  RMS error = " << cr.rms_error << "\n"
            << "  Peak SNR = " << cr.PSNR << "\n"
            << "  Max error  = " << cr.maxerror;
        if (cr.maxerror != 0) {
            const std::vector<std::string>& names =
                cr.maxc < A.nchannels() ? A.spec().channelnames : B.spec().channelnames;
            out << " @ (" << cr.maxx << ", " << cr.maxy << ", " << names.at(cr.maxc) << ")"
                << "  values are " << values_at(A, cr.maxx, cr.maxy, cr.maxz) << " vs "
                << values_at(B, cr.maxx, cr.maxy, cr.maxz);
        }
        out << "\n";
        for (const OIIO::imagesize_t count : {cr.nwarn, cr.nfail})
            if (count)
                out << "  " << count << (count == 1 ? " pixel (" : " pixels (") << percent(count, A)
                    << "%) over " << kDiffThreshold << "\n";
    }
    const bool passed = cr.nfail == 0 && !cr.error;
    out << (passed ? (cr.nwarn ? "WARNING" : "PASS") : "FAILURE") << "\n";
    return passed;
}

}  // namespace statmc::tool
