#include "temporal_frames.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "denoise_input.h"
#include "method_stages.h"
#include "statmc/core/sample_independence.h"
#include "statmc/core/temporal_merge.h"
#include "statmc/layers/float_pixels.h"
#include "statmc/layers/frame_match.h"
#include "statmc/layers/guide_layers.h"
#include "statmc/layers/imagebufalgo_forms.h"
#include "statmc/layers/layer_error.h"
#include "statmc/layers/layer_lookup.h"
#include "statmc/layers/sample_provenance.h"

namespace statmc::denoising {

using layers::LayerError;
using layers::Statistic;
using layers::StatisticsChannels;

namespace {

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

}  // namespace

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
              &StatisticsView::bc_variance, &StatisticsView::bc_moment3})
            take((shape.*member)[c], (values.*member)[c]);
    }
    shape.variance_of_mean = values.variance_of_mean;
    return shape;
}

}  // namespace statmc::denoising
