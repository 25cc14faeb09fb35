#include "statmc/verify/verify.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <OpenImageIO/imagebufalgo.h>

#include "statmc/core/filter.h"
#include "statmc/core/method.h"
#include "statmc/core/variance_filter.h"
#include "statmc/denoise/denoise.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/frame_match.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/renderer_presets.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/layers/statistics_validation.h"

namespace statmc {

namespace {

using layers::LayerError;
using layers::Statistic;
using layers::StatisticsChannels;

std::string label(const OIIO::ImageBuf& image, const char* role)
{
    return image.name().empty() ? std::string(role)
                                : std::string(role) + " (" + std::string(image.name()) + ")";
}

// The statistics under the contract's names: `in` itself, or what a renderer's preset maps.
const OIIO::ImageBuf& contract_statistics(const OIIO::ImageBuf& in, const std::string& from,
                                          layers::ImportedImage& scratch)
{
    const std::string preset = layers::resolve_renderer_preset(in.spec(), from);
    if (preset.empty() || preset == "statmc")
        return in;
    scratch = layers::statistics_from_preset(in, preset);
    return scratch.image;
}

// The candidate's three channels: `layer`'s, or R,G,B (a renderer's beauty by its preset).
std::vector<ConstPlane> candidate_planes(const OIIO::ImageBuf& candidate, const std::string& layer,
                                         layers::ImportedImage& imported, OIIO::ImageBuf& floats)
{
    const OIIO::ImageBuf& named =
        layer.empty() ? layers::contract_beauty(candidate, imported) : candidate;
    const OIIO::ImageBuf& pixels = layers::local_float_pixels(named, floats);
    std::vector<int> indices;
    if (layer.empty()) {
        for (const char* c : {"R", "G", "B"})
            indices.push_back(pixels.spec().channelindex(c));
        if (std::count(indices.begin(), indices.end(), -1) > 0)
            throw LayerError(label(candidate, "the candidate") +
                             " has no R,G,B; name its layer with candidate=");
    } else {
        indices = layers::require_guide_layer(pixels.spec(), layer, true);
    }
    std::vector<ConstPlane> planes;
    for (int index : indices)
        planes.push_back(layers::channel_plane(pixels, index));
    return planes;
}

void require_finite(const std::vector<ConstPlane>& planes, const OIIO::ImageBuf& candidate,
                    const OIIO::ROI& roi, int x0, int y0)
{
    for (int y = roi.ybegin; y < roi.yend; ++y)
        for (int x = roi.xbegin; x < roi.xend; ++x)
            for (std::size_t c = 0; c < planes.size(); ++c)
                if (!std::isfinite(planes[c](x - x0, y - y0)))
                    throw LayerError(label(candidate, "the candidate") + " holds NaN or Inf at " +
                                     "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                     "), channel " + std::to_string(c));
}

// How the test's variances are moderated: as the default ladder's, but a pixel whose
// samples all agree does not borrow its neighbours' s² outright: at many samples that
// agreement is evidence (the inside of a light), and at few the moderation's prior already
// lifts it.
VarianceFilterOptions test_moderation()
{
    VarianceFilterOptions v = method_settings(Method::Default).stages.ladder.variance;
    v.borrow_without_interval = false;
    // The test's degrees of freedom are n − 1 + d₀ (candidate_test.h), so its variances
    // weigh the pixel's own s² by n − 1 as well.
    v.own_dof_from_scatter = false;
    return v;
}

// The smallest ROI (within `roi`) holding every rejected pixel; undefined when none is.
OIIO::ROI rejected_box(const std::vector<std::uint8_t>& rejected, const OIIO::ROI& roi,
                       const OIIO::ImageSpec& spec)
{
    OIIO::ROI box;
    for (int y = roi.ybegin; y < roi.yend; ++y)
        for (int x = roi.xbegin; x < roi.xend; ++x)
            if (rejected[std::size_t(y - spec.y) * spec.width + (x - spec.x)]) {
                if (!box.defined())
                    box = OIIO::ROI(x, x + 1, y, y + 1);
                box.xbegin = std::min(box.xbegin, x);
                box.xend = std::max(box.xend, x + 1);
                box.ybegin = std::min(box.ybegin, y);
                box.yend = std::max(box.yend, y + 1);
            }
    return box;
}

// `in` copied into `dst` as float, with the channel `name` after its own (zero), unless it
// has one already (an image verified before): one copy of the image, not two.
void copy_with_map_channel(OIIO::ImageBuf& dst, const OIIO::ImageBuf& in, const std::string& name)
{
    const int n = in.nchannels();
    const bool has_map = in.spec().channelindex(name) >= 0;
    std::vector<int> order(n);
    std::vector<float> values(n, 0.f);
    std::vector<std::string> names = in.spec().channelnames;
    for (int c = 0; c < n; ++c)
        order[c] = c;
    if (!has_map) {
        order.push_back(-1);
        values.push_back(0.f);
        names.push_back(name);
    }
    if (!OIIO::ImageBufAlgo::channels(dst, in, int(order.size()), order, values, names))
        throw std::runtime_error("verify: " + dst.geterror());
}

bool verify_impl(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src_in, const OIIO::ImageBuf& candidate,
                 const VerifyOptions& opt, const OIIO::ROI& roi_in, int nthreads)
{
    if (const std::string problem = opt.denoise.validate(); !problem.empty())
        throw std::invalid_argument("verify: " + problem);
    // In place: the statistics must outlive the first write to dst.
    OIIO::ImageBuf own_copy;
    if (&dst == &src_in)
        own_copy.copy(src_in, OIIO::TypeFloat);
    const OIIO::ImageBuf& src = &dst == &src_in ? own_copy : src_in;
    layers::require_same_frame(candidate.spec(), src.spec(),
                               label(candidate, "the candidate") + " and " +
                                   label(src, "the statistics"));

    OIIO::ImageBuf floats;
    layers::ImportedImage imported;
    const OIIO::ImageBuf& in =
        contract_statistics(layers::local_float_pixels(src, floats), opt.denoise.from, imported);
    const OIIO::ImageSpec& spec = in.spec();
    const OIIO::ROI roi = roi_in.defined() ? OIIO::roi_intersection(roi_in, in.roi()) : in.roi();
    if (roi.width() <= 0 || roi.height() <= 0)
        throw std::invalid_argument("verify: the ROI does not overlap the data window");

    const StatisticsChannels ch = layers::find_statistics(spec, opt.denoise.aov);
    if (!ch.has(Statistic::Variance))
        throw LayerError(layers::missing_layer_message(
            spec, layers::statistic_layer(ch.aov, Statistic::Variance), ch.suffixes, "layer",
            "verify tests the candidate against each pixel's variance"));
    if (ch.channels() != 3)
        throw LayerError("verify: " + layers::describe_layer(ch.aov, ch.suffixes) + " has " +
                         std::to_string(ch.channels()) + " channels; a candidate has 3");
    layers::ValidationOptions validation;
    validation.roi = in.roi();
    if (const auto problems = layers::validate_statistics(in, ch, validation); !problems.empty())
        throw LayerError(layers::join_messages(problems));

    layers::ImportedImage imported_candidate;
    OIIO::ImageBuf candidate_floats;
    const std::vector<ConstPlane> cand =
        candidate_planes(candidate, opt.candidate_layer, imported_candidate, candidate_floats);
    require_finite(cand, candidate, roi, spec.x, spec.y);

    const StatisticsView view = layers::statistics_view(in, ch);
    const VarianceFilterOptions moderation = test_moderation();
    CandidateTestOptions test = opt.test;
    test.prior_dof = moderation.prior_dof;  // the moderated variances' degrees of freedom
    const std::vector<float> variances = denoise_variances(
        view, TestDomain::Untransformed, {}, moderation, layers::thread_count(nthreads));
    std::vector<std::uint8_t> rejected =
        test_candidate(view, variances, cand, test, layers::thread_count(nthreads));

    // A renderer's file comes out under the contract's names, as --passes writes them. The
    // fallback's denoise runs in place on the copy, which already holds the map's channel.
    const std::string map_name = layers::diagnostics_channel(ch.aov, layers::kRejectedChannel);
    copy_with_map_channel(dst, in, map_name);
    const OIIO::ROI box = rejected_box(rejected, roi, spec);
    if (box.defined() && opt.fallback == VerifyFallback::Denoise) {
        DenoiseImageOptions contract = opt.denoise;
        contract.from = "statmc";
        const int b = test.box_radius;
        const OIIO::ROI boxes = OIIO::roi_intersection(
            OIIO::ROI(box.xbegin - b, box.xend + b, box.ybegin - b, box.yend + b), roi);
        // Every box the second test reads around a rejected pixel holds the fallback's
        // estimate (outside `roi`, the pixels' means).
        if (!denoise(dst, dst, grown_mask(rejected, spec.width, spec.height, b), contract, boxes,
                     nthreads))
            return false;
        // A rejected candidate is replaced only where the fallback's estimate, tested as the
        // pixel's mean would be, rejects it too: elsewhere the two differ by less than the
        // samples resolve, and switching would buy nothing they can justify (§15).
        const std::vector<std::uint8_t> against_fallback =
            test_candidate(layers::statistics_view(dst, ch), variances, cand, test,
                           layers::thread_count(nthreads));
        for (std::size_t i = 0; i < rejected.size(); ++i)
            if (!against_fallback[i])
                rejected[i] = 0;
    }
    // Planes of dst over its data window, as cand's are: (0, 0) is (spec.x, spec.y).
    Plane means[3];
    for (int c = 0; c < 3; ++c)
        means[c] =
            layers::channel_plane(dst, dst.spec().channelindex(ch.channel(Statistic::Mean, c)));
    const Plane map = layers::channel_plane(dst, dst.spec().channelindex(map_name));
    std::size_t count = 0;
    for (int y = roi.ybegin - spec.y; y < roi.yend - spec.y; ++y)
        for (int x = roi.xbegin - spec.x; x < roi.xend - spec.x; ++x) {
            const std::uint8_t bits = rejected[std::size_t(y) * spec.width + x];
            map(x, y) = float(bits);
            count += bits != 0;
            if (!bits)
                for (int c = 0; c < 3; ++c)
                    means[c](x, y) = cand[c](x, y);
        }
    dst.specmod().attribute(layers::attr::kDenoised, 1);
    dst.specmod().attribute(layers::attr::kVerifyRejected,
                            float(double(count) / (double(roi.width()) * roi.height())));
    return true;
}

}  // namespace

bool verify(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const OIIO::ImageBuf& candidate,
            const VerifyOptions& opt, OIIO::ROI roi, int nthreads)
{
    return layers::errors_on(dst, "verify",
                             [&] { return verify_impl(dst, src, candidate, opt, roi, nthreads); });
}

OIIO::ImageBuf verify(const OIIO::ImageBuf& src, const OIIO::ImageBuf& candidate,
                      const VerifyOptions& opt, OIIO::ROI roi, int nthreads)
{
    return layers::returned_image("verify", [&](OIIO::ImageBuf& dst) {
        return verify(dst, src, candidate, opt, roi, nthreads);
    });
}

}  // namespace statmc
