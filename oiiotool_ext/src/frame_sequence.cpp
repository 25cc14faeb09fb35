#include "frame_sequence.h"

#include <algorithm>
#include <stdexcept>

#include <OpenImageIO/filesystem.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "statmc/layers/frame_match.h"
#include "statmc/layers/openexr_check.h"
#include "statmc/plugin_host/host_error.h"

namespace statmc::tool {

std::string frame_pattern(const std::string& text, std::string* range)
{
    try {
        return layers::frame_pattern(text, range);
    } catch (const std::invalid_argument& e) {
        throw host::HostError(e.what());
    }
}

std::vector<int> parse_frame_list(const std::string& spec)
{
    const std::optional<std::vector<int>> list = layers::frame_list(spec);
    if (!list)
        throw host::HostError("--frames: cannot read '" + spec +
                              "' as frames (e.g. 1-48, 1-48x2, 3,5,10-20; at most " +
                              std::to_string(layers::kMaxFrames) + " frames)");
    std::vector<int> sorted = *list;
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
        throw host::HostError("--frames " + spec + ": frame " + std::to_string(*twice) +
                              " is listed twice");
    return *list;
}

std::vector<int> frames_on_disk(const std::string& text, const std::string& pattern)
{
    std::vector<int> frames;
    std::vector<std::string> names;
    OIIO::Filesystem::scan_for_matching_filenames(pattern, frames, names);
    if (frames.empty())
        throw host::HostError(text + ": the frame pattern matches no file (looked for " +
                              frame_path(pattern, 1) +
                              " and the like); give --frames to name them");
    std::sort(frames.begin(), frames.end());
    return frames;
}

FrameSequence::FrameSequence(std::string pattern, std::vector<int> frames)
    : pattern_(std::move(pattern)), frames_(std::move(frames))
{
}

void FrameSequence::remember(int frame, const OIIO::ImageBuf& image)
{
    position(frame);
    if (read_.count(frame))
        return;
    auto copy = std::make_shared<OIIO::ImageBuf>();
    if (!copy->copy(image))
        throw host::HostError(frame_path(pattern_, frame) +
                              ": cannot keep a copy: " + copy->geterror());
    read_[frame] = std::move(copy);
}

int FrameSequence::position(int frame) const
{
    const auto it = std::find(frames_.begin(), frames_.end(), frame);
    if (it == frames_.end())
        throw host::HostError(frame_path(pattern_, frame) + ": frame " + std::to_string(frame) +
                              " is not in the sequence");
    return int(it - frames_.begin());
}

std::vector<const OIIO::ImageBuf*> FrameSequence::around(int frame, const std::vector<int>& offsets,
                                                         const layers::ReadOptions& options)
{
    const int at = position(frame);
    check_frames_match(options);
    std::vector<int> wanted, missing;
    for (int offset : offsets) {
        reach_ = std::max(reach_, std::abs(offset));
        const int k = at + offset;
        wanted.push_back(k >= 0 && k < int(frames_.size()) ? frames_[k] : 0);
        if (k >= 0 && k < int(frames_.size()) && !read_.count(frames_[k]) &&
            std::find(missing.begin(), missing.end(), frames_[k]) == missing.end())
            missing.push_back(frames_[k]);
    }
    read_missing(missing, options);
    std::vector<const OIIO::ImageBuf*> images;
    for (std::size_t i = 0; i < offsets.size(); ++i) {
        const int k = at + offsets[i];
        images.push_back(k >= 0 && k < int(frames_.size()) ? read_.at(wanted[i]).get() : nullptr);
    }
    return images;
}

// Before any pixels are read, so that a mismatch late in the sequence stops the run before
// its first output rather than at that frame.
void FrameSequence::check_frames_match(const layers::ReadOptions& options)
{
    if (frames_checked_)
        return;
    const std::string first = frame_path(pattern_, frames_.front());
    const OIIO::ImageSpec spec = layers::read_image_header(first, options);
    for (std::size_t k = 1; k < frames_.size(); ++k) {
        const std::string path = frame_path(pattern_, frames_[k]);
        layers::require_matching_specs(layers::read_image_header(path, options), path, spec, first);
    }
    frames_checked_ = true;
}

// The first missing frame is read alone and sets the size of one; the rest are read as
// many at a time as the budget has room for beside the frames held, and all of them must
// fit: the temporal merge holds them together.
void FrameSequence::read_missing(const std::vector<int>& frames, const layers::ReadOptions& options)
{
    if (frames.empty())
        return;
    auto read = [&](int frame) {
        return std::make_shared<OIIO::ImageBuf>(
            layers::read_image_file(frame_path(pattern_, frame), options));
    };
    std::size_t first = 0;
    if (read_.empty())
        read_[frames[first++]] = read(frames.front());
    const OIIO::ImageBuf& sample = *read_.begin()->second;
    const std::uint64_t bytes =
        std::max<std::uint64_t>(1, std::uint64_t(sample.spec().image_pixels()) *
                                       std::uint64_t(sample.spec().nchannels) * sizeof(float));
    const std::uint64_t budget =
        options.max_memory > 0 ? options.max_memory : layers::default_read_budget();
    const std::uint64_t held = read_.size() + (frames.size() - first);
    if (held * bytes > budget)
        throw host::HostError(frame_path(pattern_, frames.front()) + ": the " +
                              std::to_string(held) + " frames held at once (" +
                              std::to_string(bytes >> 20) +
                              " MiB each) exceed the memory budget of " +
                              std::to_string(budget >> 20) + " MiB (--max-memory)");
    const int room = int(std::min<std::uint64_t>(budget / bytes - read_.size(), 64));
    std::vector<std::shared_ptr<OIIO::ImageBuf>> images(frames.size());
    tbb::task_arena arena(std::max(1, std::min(room, int(frames.size() - first))));
    arena.execute([&] {
        tbb::parallel_for(first, frames.size(),
                          [&](std::size_t k) { images[k] = read(frames[k]); });
    });
    for (std::size_t k = first; k < frames.size(); ++k)
        read_[frames[k]] = std::move(images[k]);
}

void FrameSequence::forget_beyond_reach(int frame)
{
    const int at = position(frame);
    for (auto it = read_.begin(); it != read_.end();) {
        const int k = position(it->first);
        it = std::abs(k - at) > reach_ ? read_.erase(it) : std::next(it);
    }
}

}  // namespace statmc::tool
