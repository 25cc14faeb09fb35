// The denoise operator as a pipeline (docs/filter-design.md, "The operator"): the input
// brought to the contract's form once (denoise_input.h), one run per lead layer
// (layer_run.h: statistics, stages, frames, filter, means written), the renderer's names
// restored, and the header's record of what was done.
#include "statmc/denoise/denoise.h"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "denoise_input.h"
#include "denoised_image.h"
#include "layer_run.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_names.h"

namespace statmc {

namespace {

// The runs `opt` asks for: one, whose joint AOVs share its membership; or, without joint,
// one per listed AOV after the lead, each by its own test.
std::vector<DenoiseImageOptions> runs_of(const DenoiseImageOptions& opt)
{
    if (opt.joint || opt.aovs.empty())
        return {opt};
    std::vector<DenoiseImageOptions> runs;
    DenoiseImageOptions one = opt;
    one.aovs.clear();
    runs.push_back(one);
    for (const std::string& aov : opt.aovs) {
        one.aov = aov;
        runs.push_back(one);
    }
    return runs;
}

// Each note once, in the order the runs gave them.
void add_notes(std::vector<std::string>& notes, const std::string& note)
{
    if (!note.empty() && std::find(notes.begin(), notes.end(), note) == notes.end())
        notes.push_back(note);
}

// The header of a denoised image: denoised, which layers, and which stages were left out.
void record(OIIO::ImageBuf& result, const DenoiseImageOptions& opt,
            const std::vector<std::string>& skipped)
{
    OIIO::ImageSpec& spec = result.specmod();
    spec.attribute(layers::attr::kDenoised, 1);
    spec.attribute(layers::attr::kDenoisedLayers, denoising::with_denoised_layers(spec, opt));
    std::string text;
    for (const std::string& note : skipped)
        text += (text.empty() ? "" : "; ") + note;
    if (!text.empty())
        spec.attribute(layers::attr::kDenoiseSkipped, text);
    else
        spec.erase_attribute(layers::attr::kDenoiseSkipped);
}

bool denoise_impl(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
                  const PixelMask& where, const DenoiseImageOptions& opt, const OIIO::ROI& roi,
                  int nthreads)
{
    denoising::check_input(src);
    if (const std::string why = opt.validate(); !why.empty())
        throw std::invalid_argument(why);
    OIIO::ImageBuf scratch;
    const OIIO::ImageBuf& in = layers::local_float_pixels(src, scratch);
    const std::string renderer = denoising::renderer_of(in, opt.from);

    // The image the runs write in place: another renderer's, imported once under the
    // contract's names (a new image); the input itself (or its float copy) when dst is src;
    // else none, and the first run makes the float copy. An error before a run's writes
    // leaves dst as it was.
    denoising::ContractInput imported;
    OIIO::ImageBuf copy;
    OIIO::ImageBuf* work = nullptr;
    if (!renderer.empty()) {
        imported = denoising::imported_input(in, neighbours, renderer);
        work = &imported.image;
    } else if (&dst == &src) {
        work = &in == &src ? &dst : &scratch;
    }
    const FrameNeighbours frames = renderer.empty() ? neighbours : imported.neighbours();

    std::vector<std::string> skipped;
    for (const DenoiseImageOptions& run : runs_of(opt)) {
        if (work) {
            add_notes(skipped,
                      denoising::denoise_layer(*work, *work, frames, run, roi, where, nthreads));
        } else {
            add_notes(skipped,
                      denoising::denoise_layer(in, copy, frames, run, roi, where, nthreads));
            work = &copy;
        }
    }
    if (!renderer.empty()) {
        OIIO::ImageBuf result = denoising::with_renderer_names(in, *work, imported, opt);
        record(result, opt, skipped);
        dst = std::move(result);
        return true;
    }
    record(*work, opt, skipped);
    if (work != &dst)
        dst = std::move(*work);
    return true;
}

}  // namespace

bool denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const DenoiseImageOptions& opt,
             OIIO::ROI roi, int nthreads)
{
    return denoise(dst, src, FrameNeighbours{}, opt, roi, nthreads);
}

bool denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
             const DenoiseImageOptions& opt, OIIO::ROI roi, int nthreads)
{
    return layers::errors_on(dst, "denoise", [&] {
        return denoise_impl(dst, src, neighbours, PixelMask{}, opt, roi, nthreads);
    });
}

bool denoise(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const PixelMask& where,
             const DenoiseImageOptions& opt, OIIO::ROI roi, int nthreads)
{
    return layers::errors_on(dst, "denoise", [&] {
        return denoise_impl(dst, src, FrameNeighbours{}, where, opt, roi, nthreads);
    });
}

OIIO::ImageBuf denoise(const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
                       const DenoiseImageOptions& opt, OIIO::ROI roi, int nthreads)
{
    return layers::returned_image("denoise", [&](OIIO::ImageBuf& dst) {
        return denoise(dst, src, neighbours, opt, roi, nthreads);
    });
}

OIIO::ImageBuf denoise(const OIIO::ImageBuf& src, const DenoiseImageOptions& opt, OIIO::ROI roi,
                       int nthreads)
{
    return layers::returned_image(
        "denoise", [&](OIIO::ImageBuf& dst) { return denoise(dst, src, opt, roi, nthreads); });
}

}  // namespace statmc
