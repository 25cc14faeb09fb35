#include "statmc/denoise/denoise.h"

#include <cstring>
#include <stdexcept>
#include <vector>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imagebufalgo_util.h>

#include "statmc/core/context_channel.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/radius_ladder.h"
#include "statmc/core/sample_independence.h"
#include "statmc/core/temporal_merge.h"
#include "statmc/core/variance_filter.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/frame_match.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/layer_names.h"
#include "statmc/layers/renderer_presets.h"
#include "statmc/layers/sample_provenance.h"
#include "statmc/layers/statistics_layers.h"
#include "statmc/layers/statistics_validation.h"
#include "statmc/layers/view_window.h"

namespace statmc {

namespace {

using layers::LayerError;
using layers::Statistic;
using layers::StatisticsChannels;

// What is written (the ROI within the data window) and what the filter reads: the ROI
// grown by the radius, so that ROI pixels come out exactly as in a full-frame run.
struct Regions {
    OIIO::ROI output;
    OIIO::ROI input;
};

Regions regions_for(const OIIO::ImageBuf& src, const OIIO::ROI& roi, int radius)
{
    const OIIO::ROI data = src.roi();
    const OIIO::ROI output = roi.defined() ? OIIO::roi_intersection(roi, data) : data;
    if (output.width() <= 0 || output.height() <= 0)
        throw std::invalid_argument("the ROI does not overlap the data window");
    OIIO::ROI input = output;
    input.xbegin -= radius;
    input.xend += radius;
    input.ybegin -= radius;
    input.yend += radius;
    return {output, OIIO::roi_intersection(input, data)};
}

void check_input(const OIIO::ImageBuf& src)
{
    if (!src.initialized())
        throw std::invalid_argument("uninitialized input image");
    if (src.deep())
        throw std::invalid_argument("deep images are not supported");
    if (src.spec().depth > 1)
        throw std::invalid_argument("volume images are not supported");
}

TestDomain choose_domain(const OIIO::ImageSpec& spec, const StatisticsChannels& ch,
                         TestDomainChoice choice)
{
    switch (choice) {
    case TestDomainChoice::Auto:
        if (ch.has_box_cox())
            return TestDomain::BoxCox;
        if (!ch.has(Statistic::Variance))
            throw LayerError(layers::missing_layer_message(
                spec, layers::statistic_layer(ch.aov, Statistic::Variance), ch.suffixes, "layer",
                "denoising needs it or the Box-Cox layers (boxcoxMean, "
                "boxcoxVariance, boxcoxM3)"));
        return TestDomain::Untransformed;
    case TestDomainChoice::BoxCox:
        for (Statistic stat :
             {Statistic::BoxCoxMean, Statistic::BoxCoxVariance, Statistic::BoxCoxMoment3})
            layers::require_statistic(spec, ch, stat);
        return TestDomain::BoxCox;
    case TestDomainChoice::Untransformed:
        layers::require_statistic(spec, ch, Statistic::Variance);
        return TestDomain::Untransformed;
    }
    throw std::invalid_argument("unknown test domain");
}

// Only the statistics the stages read are checked and viewed: the test's, and the
// untransformed variance for the radius ladder (`variance`).
StatisticsChannels used_channels(StatisticsChannels ch, TestDomain domain, bool variance)
{
    for (auto* v : {&ch.moment3, &ch.moment4, &ch.bc_moment4})
        v->clear();
    if (domain == TestDomain::BoxCox) {
        if (!variance)
            ch.variance.clear();
    } else {
        ch.bc_mean.clear();
        ch.bc_variance.clear();
        ch.bc_moment3.clear();
    }
    return ch;
}

void check_statistics(const OIIO::ImageBuf& in, const StatisticsChannels& ch,
                      const DenoiseImageOptions& opt, const OIIO::ROI& region)
{
    layers::ValidationOptions options;
    options.nonfinite_is_problem = opt.nonfinite == NonfinitePolicy::Error;
    options.roi = region;
    const auto problems = layers::validate_statistics(in, ch, options);
    if (!problems.empty())
        throw LayerError(layers::join_messages(problems));
}

std::array<ConstPlane, 3> guide(const OIIO::ImageBuf& in, GuideUse use, const std::string& layer,
                                bool colour)
{
    if (use == GuideUse::Off)
        return {};
    const std::vector<int> indices = use == GuideUse::Required
                                         ? layers::require_guide_layer(in.spec(), layer, colour)
                                         : layers::find_guide_layer(in.spec(), layer, colour);
    return indices.empty() ? std::array<ConstPlane, 3>{} : layers::guide_planes(in, indices);
}

// What the filter gives over the input region, dense: the means channel-major, and the
// diagnostics planes when asked for.
struct Filtered {
    std::vector<float> means, members, effective_samples;
};

// The lead's estimators, with the context channel when `context` > 0 (context_channel.h).
EstimatorImage lead_estimators(const StatisticsView& stats, TestDomain domain,
                               const DenoiseOptions& options, int context, int nthreads)
{
    EstimatorImage est = estimators_from_statistics(stats, domain);
    if (context == 0)
        return est;
    return with_context(est, context_source_channel(est.channels), context, options.firefly_ratio,
                        layers::thread_count(nthreads));
}

// `est` (built from `stats` by lead_estimators) filtered; with `ladder`, each pixel at its
// ICI radius (no diagnostics then).
Filtered filter_region(const StatisticsView& stats, const EstimatorImage& est, const Guides& guides,
                       const DenoiseOptions& options, bool diagnostics,
                       const RadiusLadderOptions* ladder, int nthreads)
{
    const std::size_t pixels = std::size_t(stats.width) * stats.height;
    Filtered f;
    f.means.resize(pixels * stats.channels);
    std::vector<Plane> out;  // none for the context channel, which is only tested
    for (int c = 0; c < stats.channels; ++c)
        out.push_back(dense_plane(f.means.data() + c * pixels, stats.width));
    FilterDiagnostics planes;
    if (diagnostics) {
        f.members.resize(pixels);
        f.effective_samples.resize(pixels);
        planes.members = dense_plane(f.members.data(), stats.width);
        planes.effective_samples = dense_plane(f.effective_samples.data(), stats.width);
    }
    if (ladder)
        filter_with_radius_ladder(stats, est, guides, options, out, *ladder,
                                  layers::thread_count(nthreads));
    else
        filter(est, guides, options, out, planes, layers::thread_count(nthreads));
    return f;
}

// An AOV averaged with the members and weights of the lead's test: `lead`, the lead's
// estimators, with the AOV's means put in as the values (docs/method.md §14). The
// estimators are built once for all the AOVs; only their values change.
Filtered filter_joint_aov(EstimatorImage& lead, const StatisticsView& aov, const Guides& guides,
                          const DenoiseOptions& options, int nthreads)
{
    const int own = lead.channels - lead.context_channels;  // the context's are only tested
    for (int c = 0; c < own; ++c)
        for (int y = 0; y < lead.height; ++y)
            for (int x = 0; x < lead.width; ++x)
                lead.value[lead.index(c, x, y)] = aov.mean[c](x, y);
    Filtered f;
    f.means.resize(lead.pixels() * own);
    std::vector<Plane> out;
    for (int c = 0; c < own; ++c)
        out.push_back(dense_plane(f.means.data() + c * lead.pixels(), lead.width));
    filter(lead, guides, options, out, {}, layers::thread_count(nthreads));
    return f;
}

// The means of `aov`, checked over `region` as the lead's statistics are: only its means
// are read, so they are all it needs besides the shared count.
// The statistics of a joint AOV, which must have as many channels as the lead.
StatisticsChannels joint_aov_channels(const OIIO::ImageSpec& spec, const std::string& aov,
                                      const StatisticsChannels& lead)
{
    StatisticsChannels ch = layers::find_statistics(spec, aov);
    if (ch.channels() != lead.channels())
        throw LayerError("aovs: " + aov + " has " + std::to_string(ch.channels()) +
                         " channels and " + (lead.aov.empty() ? "the beauty" : lead.aov) + " " +
                         std::to_string(lead.channels()) + "; joint AOVs must match");
    return ch;
}

StatisticsChannels joint_aov_means(const OIIO::ImageBuf& in, const std::string& aov,
                                   const StatisticsChannels& lead, const DenoiseImageOptions& opt,
                                   const OIIO::ROI& region)
{
    StatisticsChannels ch = joint_aov_channels(in.spec(), aov, lead);
    for (Statistic stat : layers::all_statistics())
        if (stat != Statistic::Mean)
            ch.indices(stat).clear();
    check_statistics(in, ch, opt, region);
    return ch;
}

// Whether `ch` has what the test in `domain` reads.
bool has_test_statistics(const StatisticsChannels& ch, TestDomain domain)
{
    return domain == TestDomain::BoxCox ? ch.has_box_cox() : ch.has(Statistic::Variance);
}

// Whether joint AOVs share a membership that all their tests decide: where every listed
// AOV has the test's statistics. Else the lead's test decides, and `note` says why.
bool joint_test_all(const OIIO::ImageSpec& spec, TestDomain domain, const DenoiseImageOptions& opt,
                    std::string& note)
{
    if (!opt.joint)
        return false;
    for (const std::string& aov : opt.aovs) {
        if (has_test_statistics(layers::find_statistics(spec, aov), domain))
            continue;
        note = "the joint AOVs' own tests (AOV " + aov + " has no " +
               (domain == TestDomain::BoxCox ? "Box-Cox layers" : "variance") +
               " of its own; the AOVs share " +
               (opt.aov.empty() ? std::string("the beauty") : opt.aov) + "'s test)";
        return false;
    }
    return true;
}

// The AOV's statistics that its test reads, checked over `region` like the lead's.
StatisticsChannels joint_aov_statistics(const OIIO::ImageBuf& in, const std::string& aov,
                                        const StatisticsChannels& lead, TestDomain domain,
                                        const DenoiseImageOptions& opt, const OIIO::ROI& region)
{
    const StatisticsChannels ch =
        used_channels(joint_aov_channels(in.spec(), aov, lead), domain, false);
    check_statistics(in, ch, opt, region);
    return ch;
}

// The lead and every joint AOV filtered as one image whose test is all of theirs
// (side_by_side): one membership and one set of weights for every channel, so sums hold.
// Returns the lead's output and each AOV's, in order.
std::vector<Filtered> filter_joint_all(const StatisticsView& lead,
                                       const std::vector<StatisticsView>& aovs, TestDomain domain,
                                       const Guides& guides, const DenoiseOptions& options,
                                       int nthreads)
{
    std::vector<EstimatorImage> parts = {estimators_from_statistics(lead, domain)};
    for (const StatisticsView& aov : aovs)
        parts.push_back(estimators_from_statistics(aov, domain));
    std::vector<const EstimatorImage*> pointers;
    for (const EstimatorImage& p : parts)
        pointers.push_back(&p);
    const EstimatorImage all = side_by_side(pointers);
    if (!filter_takes_channels(all.channels))
        throw std::invalid_argument(
            "joint_test=all tests " + std::to_string(all.channels) +
            " channels together; the filter takes 1 to 4, 6, 9 or 12 (at most three RGB AOVs "
            "besides the beauty), or take joint_test=aov");
    std::vector<float> means(all.pixels() * all.channels);
    std::vector<Plane> out;
    for (int c = 0; c < all.channels; ++c)
        out.push_back(dense_plane(means.data() + c * all.pixels(), all.width));
    filter(all, guides, options, out, {}, layers::thread_count(nthreads));
    std::vector<Filtered> result(parts.size());
    std::size_t at = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const std::size_t n = parts[k].pixels() * parts[k].channels;
        result[k].means.assign(means.begin() + at, means.begin() + at + n);
        at += n;
    }
    return result;
}

// A dense plane over the input region, and the channel of the image it is written to.
struct ChannelWrite {
    int channel;
    const float* dense;
};

// Writes each dense plane into its channel of `image` over the output region, row by row
// in parallel. With `source`, each row is first copied from it (same spec): copying a
// 1280×720 statistics image (~80 MB) and then patching it walked it twice, on one thread.
void write_channels(OIIO::ImageBuf& image, const OIIO::ImageBuf* source,
                    const std::vector<ChannelWrite>& writes, const Regions& regions, int nthreads)
{
    const OIIO::ImageSpec& spec = image.spec();
    const OIIO::ROI& out = regions.output;
    const OIIO::ROI& input = regions.input;
    const std::size_t row_bytes = std::size_t(spec.width) * image.pixel_stride();
    OIIO::ImageBufAlgo::parallel_image(
        image.roi(), OIIO::paropt(layers::thread_count(nthreads)), [&](OIIO::ROI rows) {
            for (int y = rows.ybegin; y < rows.yend; ++y) {
                float* to = static_cast<float*>(image.pixeladdr(spec.x, y));
                if (source)
                    std::memcpy(to, source->pixeladdr(spec.x, y), row_bytes);
                if (y < out.ybegin || y >= out.yend)
                    continue;
                const std::ptrdiff_t row =
                    std::ptrdiff_t(y - input.ybegin) * input.width() - input.xbegin;
                for (int x = out.xbegin; x < out.xend; ++x) {
                    float* pixel = to + std::size_t(x - spec.x) * spec.nchannels;
                    for (const ChannelWrite& w : writes)
                        pixel[w.channel] = w.dense[row + x];
                }
            }
        });
}

std::vector<ChannelWrite> mean_writes(const StatisticsChannels& ch, const Filtered& f,
                                      const Regions& regions)
{
    const std::size_t pixels = std::size_t(regions.input.width()) * regions.input.height();
    std::vector<ChannelWrite> writes;
    for (int c = 0; c < ch.channels(); ++c)
        writes.push_back({ch.mean[c], f.means.data() + c * pixels});
    return writes;
}

// A float copy of `in`, every channel and attribute kept, with the filtered means.
OIIO::ImageBuf denoised_copy(const OIIO::ImageBuf& in, const StatisticsChannels& ch,
                             const Filtered& f, const Regions& regions, int nthreads)
{
    OIIO::ImageBuf result(in.spec(), OIIO::InitializePixels::No);
    if (result.has_error() || !layers::has_local_float_pixels(result))
        throw std::runtime_error("cannot allocate the output image: " + result.geterror());
    write_channels(result, &in, mean_writes(ch, f, regions), regions, nthreads);
    return result;
}

// `result` with the diagnostics channels of `aov`, added (as zeros) unless an earlier
// run left them; their indices in the returned image come back in `members`/`effective`.
OIIO::ImageBuf with_diagnostics_channels(const OIIO::ImageBuf& result, const std::string& aov,
                                         int& members, int& effective)
{
    const std::string names[2] = {
        layers::diagnostics_channel(aov, layers::kMembersChannel),
        layers::diagnostics_channel(aov, layers::kEffectiveSamplesChannel)};
    const OIIO::ImageSpec& spec = result.spec();
    std::vector<int> order;
    std::vector<float> values(spec.nchannels, 0.f);
    std::vector<std::string> new_names(spec.channelnames);
    for (int c = 0; c < spec.nchannels; ++c)
        order.push_back(c);
    for (const std::string& name : names)
        if (spec.channelindex(name) < 0) {
            order.push_back(-1);
            values.push_back(0.f);
            new_names.push_back(name);
        }
    OIIO::ImageBuf extended =
        OIIO::ImageBufAlgo::channels(result, int(order.size()), order, values, new_names);
    if (extended.has_error())
        throw std::runtime_error("cannot add the diagnostics channels: " + extended.geterror());
    members = extended.spec().channelindex(names[0]);
    effective = extended.spec().channelindex(names[1]);
    return extended;
}

// The method's stages around the mean filter (the radius ladder, the context test) that
// run on this image, and the halo they read.
struct Stages {
    bool radius_ladder = false;
    int context_radius = 0;  ///< 0: no context test
    RadiusLadderOptions ladder;
    std::string skipped;  ///< the stages left out, and why ("" when none)

    // The ladder's variance filter and the context boxes read beyond the mean filter's halo.
    int halo() const
    {
        return std::max(radius_ladder ? ladder.variance.radius : 0, context_radius);
    }
};

Stages stages_for(const OIIO::ImageSpec& spec, const StatisticsChannels& all, TestDomain domain,
                  const DenoiseImageOptions& opt)
{
    Stages s;
    auto skip = [&s](const std::string& why) {
        s.skipped += (s.skipped.empty() ? "" : "; ") + why;
    };
    s.radius_ladder = opt.stages.radius_ladder;
    if (s.radius_ladder) {
        const char* why = opt.joint ? "joint AOVs share one membership; the ladder's radii "
                                      "would differ per AOV"
                          : !all.has(Statistic::Variance) ? "needs the variance layer"
                          : opt.diagnostics ? "the radius differs per pixel, so diagnostics "
                                              "cannot describe it"
                                            : nullptr;
        if (why) {
            s.radius_ladder = false;
            skip(std::string("ici (") + why + ")");
        }
    }
    if (s.radius_ladder) {
        s.ladder = opt.stages.ladder;
        // Its variance filter weighs the guides as the mean filter does.
        s.ladder.variance.sigma_albedo = opt.filter.sigma_albedo;
        s.ladder.variance.sigma_normal = opt.filter.sigma_normal;
    }
    s.context_radius = opt.stages.context_radius;
    if (s.context_radius > 0) {
        // The lead's membership alone would change: joint AOVs would no longer add up.
        std::string unused_note;
        const char* why = joint_test_all(spec, domain, opt, unused_note)
                              ? "the AOVs are tested side by side, and the filter has no "
                                "room for a context channel beside them"
                          : all.channels() >= 4 ? "the filter takes at most four channels, "
                                                  "and the layer has four without it"
                                                : nullptr;
        if (why) {
            s.context_radius = 0;
            skip(std::string("context (") + why + ")");
        }
    }
    return s;
}

// "frame t−2 (shot.0003.exr)": a neighbour as messages name it.
std::string frame_label(int offset, const OIIO::ImageBuf& frame)
{
    std::string text =
        offset < 0 ? "frame t−" + std::to_string(-offset) : "frame t+" + std::to_string(offset);
    if (!frame.name().empty())
        text += " (" + std::string(frame.name()) + ")";
    return text;
}

// The statistics of a neighbour that `centre` (the channels the stages read) selects:
// each of them must be there too.
StatisticsChannels same_statistics(const OIIO::ImageSpec& spec, const StatisticsChannels& centre)
{
    StatisticsChannels ch = layers::find_statistics(spec, centre.aov);
    if (ch.channels() != centre.channels())
        throw LayerError("its " + layers::describe_layer(centre.aov, ch.suffixes) +
                         " differs in channels from the frame denoised");
    for (Statistic stat : layers::all_statistics()) {
        if (centre.has(stat))
            layers::require_statistic(spec, ch, stat);
        else
            ch.indices(stat).clear();
    }
    return ch;
}

// A neighbour whose samples are the centre's own, by its header (one seed, overlapping
// sample ranges) or by its pixels (the noise of a static region repeated to the bit), would
// be merged as if it were more samples (docs/method.md, "Independent samples").
void require_independent_frames(const OIIO::ImageBuf& frame, const StatisticsView& frame_stats,
                                const OIIO::ImageBuf& centre, const StatisticsView& centre_stats,
                                const std::string& what)
{
    const layers::SampleProvenance a = layers::read_sample_provenance(frame.spec()),
                                   b = layers::read_sample_provenance(centre.spec());
    // statmc-render sequences written before the header held each frame's own seed carry
    // the sequence's seed and their frame numbers, and drew with the two mixed.
    const OIIO::ParamValue* fa = frame.spec().find_attribute(layers::attr::kFrame, OIIO::TypeInt);
    const OIIO::ParamValue* fb = centre.spec().find_attribute(layers::attr::kFrame, OIIO::TypeInt);
    const bool mixed_by_frame = fa && fb && fa->get_int() != fb->get_int();
    const std::string fix =
        ": merged over time they would count twice. Render every frame with its own seed "
        "(statmc-render --frames and statmc-farm do; Blender: Render Properties > Sampling > "
        "Advanced > the clock icon beside Seed, scene.cycles.use_animated_seed = True)";
    if (layers::shares_samples(a, b) && !mixed_by_frame)
        throw LayerError(what + " drew the same samples (" + layers::describe(a) + ")" + fix);
    const SharedNoise shared = shared_noise(centre_stats, frame_stats);
    if (shared.same_samples())
        throw LayerError(what + " repeat the same noise in " + std::to_string(shared.identical) +
                         " of " + std::to_string(shared.noisy) +
                         " noisy pixels, bit for bit: they were rendered with one seed" + fix);
}

// statmc:denoisedLayers of `spec` with the layers `opt` denoises added: what a later
// denoise of the file is warned about.
std::string with_denoised_layers(const OIIO::ImageSpec& spec, const DenoiseImageOptions& opt)
{
    std::string layers = spec.get_string_attribute(layers::attr::kDenoisedLayers);
    std::vector<std::string> now = {opt.aov.empty() ? std::string("beauty") : opt.aov};
    now.insert(now.end(), opt.aovs.begin(), opt.aovs.end());
    for (const std::string& layer : now)
        if (("," + layers + ",").find("," + layer + ",") == std::string::npos)
            layers += (layers.empty() ? "" : ",") + layer;
    return layers;
}

// `src` followed by its neighbours, in time order, as the temporal merge takes them.
struct Sequence {
    std::vector<const OIIO::ImageBuf*> frames;  // float pixels
    std::vector<int> offsets;                   // relative to the centre
    int centre = 0;
    std::vector<OIIO::ImageBuf> scratch;  // float copies of non-float neighbours
};

Sequence sequence_of(const OIIO::ImageBuf& in, const FrameNeighbours& neighbours, int reach)
{
    Sequence seq;
    const int before = std::min<int>(reach, int(neighbours.previous.size()));
    const int after = std::min<int>(reach, int(neighbours.next.size()));
    seq.scratch.resize(before + after + 1);
    auto add = [&](const OIIO::ImageBuf* frame, int offset) {
        if (offset == 0) {
            seq.centre = int(seq.frames.size());
            seq.frames.push_back(&in);
        } else {
            if (!frame)
                throw std::invalid_argument(frame_label(offset, OIIO::ImageBuf()) + " is null");
            try {
                check_input(*frame);
            } catch (const std::invalid_argument& e) {
                throw std::invalid_argument(frame_label(offset, *frame) + ": " + e.what());
            }
            seq.frames.push_back(
                &layers::local_float_pixels(*frame, seq.scratch[seq.frames.size()]));
        }
        seq.offsets.push_back(offset);
    };
    for (int k = before; k >= 1; --k)
        add(neighbours.previous[k - 1], -k);
    add(nullptr, 0);
    for (int k = 1; k <= after; ++k)
        add(neighbours.next[k - 1], k);
    return seq;
}

// The centre's statistics with the members of its neighbours merged in, over the whole
// data window (a member's correspondence may lie anywhere in it).
StatisticsPlanes merged_over_time(const OIIO::ImageBuf& in, const StatisticsChannels& ch,
                                  TestDomain domain, const FrameNeighbours& neighbours,
                                  const DenoiseImageOptions& opt, int nthreads)
{
    const Sequence seq = sequence_of(in, neighbours, opt.temporal.frames);
    std::vector<TemporalFrame> frames;
    for (std::size_t k = 0; k < seq.frames.size(); ++k) {
        const OIIO::ImageBuf& frame = *seq.frames[k];
        const int offset = seq.offsets[k];
        StatisticsChannels frame_ch = ch;
        try {
            if (offset != 0) {
                layers::require_same_frame(frame.spec(), in.spec(),
                                           frame_label(offset, frame) + " and the frame denoised");
                frame_ch = same_statistics(frame.spec(), ch);
                check_statistics(frame, frame_ch, opt, {});
                require_independent_frames(frame, layers::statistics_view(frame, frame_ch), in,
                                           layers::statistics_view(in, ch),
                                           "it and the frame denoised");
            }
            const std::array<ConstPlane, 2> motion = layers::motion_planes(frame);
            frames.push_back({layers::statistics_view(frame, frame_ch), motion[0], motion[1]});
        } catch (const LayerError& e) {
            throw LayerError(offset == 0 ? e.what() : frame_label(offset, frame) + ": " + e.what());
        }
        if (frames.back().has_motion() != frames.front().has_motion()) {
            const std::size_t with = frames.back().has_motion() ? k : 0, without = k - with;
            throw LayerError("the motion layer (motion.X, motion.Y) is in " +
                             (seq.offsets[with] == 0
                                  ? std::string("the frame denoised")
                                  : frame_label(seq.offsets[with], *seq.frames[with])) +
                             " but not in " +
                             (seq.offsets[without] == 0
                                  ? std::string("the frame denoised")
                                  : frame_label(seq.offsets[without], *seq.frames[without])) +
                             ": temporal denoising follows it in every frame or in none");
        }
    }
    return merge_temporal_members(frames, seq.centre, domain, opt.temporal, opt.filter,
                                  layers::thread_count(nthreads));
}

// `shape` (the planes the stages read) with each plane taken from `values`.
StatisticsView with_planes_of(StatisticsView shape, const StatisticsView& values)
{
    auto take = [](ConstPlane& to, const ConstPlane& from) {
        if (to && !from)
            throw std::logic_error("temporal merge lost a plane");
        if (to)
            to = from;
    };
    take(shape.count, values.count);
    for (int c = 0; c < shape.channels; ++c) {
        for (auto member :
             {&StatisticsView::mean, &StatisticsView::variance, &StatisticsView::bc_mean,
              &StatisticsView::bc_variance, &StatisticsView::bc_moment3, &StatisticsView::moment3,
              &StatisticsView::moment4, &StatisticsView::bc_moment4})
            take((shape.*member)[c], (values.*member)[c]);
    }
    shape.variance_of_mean = values.variance_of_mean;
    return shape;
}

// The channel `from` holds under `to`'s name, over the whole data window.
void copy_channel(const OIIO::ImageBuf& from, const std::string& from_name, OIIO::ImageBuf& to,
                  const std::string& to_name)
{
    OIIO::ROI source = from.roi(), target = to.roi();
    source.chbegin = from.spec().channelindex(from_name);
    target.chbegin = to.spec().channelindex(to_name);
    source.chend = source.chbegin + 1;
    target.chend = target.chbegin + 1;
    std::vector<float> values(source.npixels());
    if (!from.get_pixels(source, OIIO::TypeFloat, values.data()) ||
        !to.set_pixels(target, OIIO::TypeFloat, values.data()))
        throw std::runtime_error("cannot copy the denoised channel " + from_name + " to " +
                                 to_name);
}

bool denoise_impl(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
                  const DenoiseImageOptions& opt, const OIIO::ROI& roi, int nthreads);

// Another renderer's file: its statistics are imported under the contract's names and
// denoised as such; the result is `in` with the denoised means written back to the
// renderer's own channels, every other channel kept as it was.
void denoise_imported(OIIO::ImageBuf& dst, const OIIO::ImageBuf& in,
                      const FrameNeighbours& neighbours, const std::string& preset,
                      const DenoiseImageOptions& opt, const OIIO::ROI& roi, int nthreads)
{
    const layers::ImportedImage imported = layers::statistics_from_preset(in, preset);
    std::vector<layers::ImportedImage> frames;
    FrameNeighbours imported_neighbours;
    for (const auto* side : {&neighbours.previous, &neighbours.next})
        for (const OIIO::ImageBuf* frame : *side)
            frames.push_back(layers::statistics_from_preset(*frame, preset));
    std::size_t k = 0;
    for (; k < neighbours.previous.size(); ++k)
        imported_neighbours.previous.push_back(&frames[k].image);
    for (; k < frames.size(); ++k)
        imported_neighbours.next.push_back(&frames[k].image);

    DenoiseImageOptions contract = opt;
    contract.from = "statmc";
    OIIO::ImageBuf denoised;
    denoise_impl(denoised, imported.image, imported_neighbours, contract, roi, nthreads);

    OIIO::ImageBuf result;
    if (!result.copy(in, OIIO::TypeFloat))
        throw std::runtime_error("cannot copy the input: " + result.geterror());
    const OIIO::ImageSpec& spec = denoised.spec();
    std::vector<std::string> denoised_aovs = {opt.aov};
    denoised_aovs.insert(denoised_aovs.end(), opt.aovs.begin(), opt.aovs.end());
    for (const std::string& aov : denoised_aovs)
        for (int c : layers::find_statistics(spec, aov).mean)
            for (const auto& [contract_name, source_name] : imported.renamed)
                if (contract_name == spec.channelnames[c])
                    copy_channel(denoised, contract_name, result, source_name);
    if (opt.diagnostics) {
        int members = -1, effective = -1;
        result = with_diagnostics_channels(result, opt.aov, members, effective);
        for (int c : {members, effective})
            copy_channel(denoised, result.spec().channelnames[c], result,
                         result.spec().channelnames[c]);
    }
    for (const char* name :
         {layers::attr::kDenoised, layers::attr::kDenoiseSkipped, layers::attr::kDenoisedLayers})
        if (const OIIO::ParamValue* value = spec.find_attribute(name))
            result.specmod().attribute(name, value->type(), value->data());
    dst = std::move(result);
}

bool denoise_impl(OIIO::ImageBuf& dst, const OIIO::ImageBuf& src, const FrameNeighbours& neighbours,
                  const DenoiseImageOptions& opt, const OIIO::ROI& roi, int nthreads)
{
    check_input(src);
    if (const std::string why = opt.validate(); !why.empty())
        throw std::invalid_argument(why);
    if (!opt.aovs.empty() && !opt.joint) {
        // Each AOV by its own test: one run per AOV, the later ones in place.
        DenoiseImageOptions one = opt;
        one.aovs.clear();
        denoise_impl(dst, src, neighbours, one, roi, nthreads);
        for (const std::string& aov : opt.aovs) {
            one.aov = aov;
            denoise_impl(dst, dst, neighbours, one, roi, nthreads);
        }
        return true;
    }
    OIIO::ImageBuf scratch;
    const OIIO::ImageBuf& in = layers::local_float_pixels(src, scratch);
    const OIIO::ImageSpec& spec = in.spec();
    if (const std::string preset = layers::resolve_renderer_preset(spec, opt.from);
        !preset.empty() && preset != "statmc") {
        denoise_imported(dst, in, neighbours, preset, opt, roi, nthreads);
        return true;
    }

    const StatisticsChannels all = layers::find_statistics(spec, opt.aov);
    const TestDomain domain = choose_domain(spec, all, opt.test);
    const Stages stages = stages_for(spec, all, domain, opt);
    const StatisticsChannels ch = used_channels(all, domain, stages.radius_ladder);
    const int halo = stages.halo();
    const Regions regions = regions_for(in, roi, opt.filter.radius + halo);
    check_statistics(in, ch, opt, regions.input);

    layers::GuidePlanes guides;
    guides.albedo = guide(in, opt.guides.albedo, opt.guides.albedo_layer, true);
    guides.normal = guide(in, opt.guides.normal, opt.guides.normal_layer, false);
    if (guides.albedo[0])
        guides.albedo_variance = layers::guide_variance_plane(in, opt.guides.albedo_layer);
    if (guides.normal[0])
        guides.normal_variance = layers::guide_variance_plane(in, opt.guides.normal_layer);

    StatisticsView full = layers::statistics_view(in, ch);
    StatisticsPlanes merged;
    if (opt.temporal.frames > 0 && (!neighbours.previous.empty() || !neighbours.next.empty())) {
        merged = merged_over_time(in, ch, domain, neighbours, opt, nthreads);
        full = with_planes_of(full, merged.view());
    }
    const int x0 = regions.input.xbegin - spec.x;
    const int y0 = regions.input.ybegin - spec.y;
    const StatisticsView window =
        layers::view_window(full, x0, y0, regions.input.width(), regions.input.height());
    const Guides window_guides{layers::shifted(guides.albedo, x0, y0),
                               layers::shifted(guides.normal, x0, y0),
                               layers::shifted(guides.albedo_variance, x0, y0),
                               layers::shifted(guides.normal_variance, x0, y0)};
    std::string joint_note;
    const bool test_all = joint_test_all(spec, domain, opt, joint_note);
    auto aov_window = [&](const StatisticsChannels& aov_ch) {
        return layers::view_window(layers::statistics_view(in, aov_ch), x0, y0,
                                   regions.input.width(), regions.input.height());
    };
    Filtered filtered;
    std::vector<std::pair<StatisticsChannels, Filtered>> joint;
    if (test_all) {
        // One filter over the lead and every AOV side by side: all their tests decide.
        std::vector<StatisticsView> views;
        for (const std::string& aov : opt.aovs) {
            joint.emplace_back(joint_aov_statistics(in, aov, ch, domain, opt, regions.input),
                               Filtered{});
            views.push_back(aov_window(joint.back().first));
        }
        std::vector<Filtered> all =
            filter_joint_all(window, views, domain, window_guides, opt.filter, nthreads);
        filtered = std::move(all[0]);
        for (std::size_t k = 0; k < joint.size(); ++k)
            joint[k].second = std::move(all[k + 1]);
    } else {
        // Built once: the joint AOVs below reuse the lead's estimators, their values swapped.
        EstimatorImage lead = lead_estimators(window, domain, opt.filter,
                                              stages.context_radius, nthreads);
        filtered = filter_region(window, lead, window_guides, opt.filter, opt.diagnostics,
                                 stages.radius_ladder ? &stages.ladder : nullptr, nthreads);
        for (const std::string& aov : opt.joint ? opt.aovs : std::vector<std::string>{}) {
            StatisticsChannels aov_ch = joint_aov_means(in, aov, ch, opt, regions.input);
            Filtered f =
                filter_joint_aov(lead, aov_window(aov_ch), window_guides, opt.filter, nthreads);
            joint.emplace_back(std::move(aov_ch), std::move(f));
        }
    }

    OIIO::ImageBuf result;
    if (&dst == &src) {
        // In place (ImageBufAlgo's dst == src): the float pixels the filter read are
        // patched, so the input is never copied. The filter's output is already apart.
        result = &in == &src ? std::move(dst) : std::move(scratch);
        write_channels(result, nullptr, mean_writes(ch, filtered, regions), regions, nthreads);
    } else {
        result = denoised_copy(in, ch, filtered, regions, nthreads);
    }
    std::vector<ChannelWrite> joint_writes;
    for (const auto& [aov_ch, f] : joint)
        for (const ChannelWrite& w : mean_writes(aov_ch, f, regions))
            joint_writes.push_back(w);
    if (!joint_writes.empty())
        write_channels(result, nullptr, joint_writes, regions, nthreads);
    if (opt.diagnostics) {
        int members = -1, effective = -1;
        result = with_diagnostics_channels(result, opt.aov, members, effective);
        write_channels(
            result, nullptr,
            {{members, filtered.members.data()}, {effective, filtered.effective_samples.data()}},
            regions, nthreads);
    }
    result.specmod().attribute(layers::attr::kDenoised, 1);
    result.specmod().attribute(layers::attr::kDenoisedLayers,
                               with_denoised_layers(result.spec(), opt));
    std::string skipped = stages.skipped;
    if (!joint_note.empty())
        skipped += (skipped.empty() ? "" : "; ") + joint_note;
    if (!skipped.empty())
        result.specmod().attribute(layers::attr::kDenoiseSkipped, skipped);
    else
        result.specmod().erase_attribute(layers::attr::kDenoiseSkipped);
    dst = std::move(result);
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
    return layers::errors_on(
        dst, "denoise", [&] { return denoise_impl(dst, src, neighbours, opt, roi, nthreads); });
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
