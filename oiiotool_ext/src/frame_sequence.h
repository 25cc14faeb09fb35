// Frame sequences as oiiotool spells them: a file name with a frame pattern (shot.#.exr,
// shot.@@@.exr, shot.%04d.exr) and a frame list (--frames 1-48, or the files on disk).
// The program runs once per frame; an input read from a pattern keeps a link to its
// sequence so that an operator can ask for the frames around it (--denoise:temporal).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "statmc/layers/exr_files.h"
#include "statmc/layers/frame_names.h"

namespace statmc::tool {

using layers::frame_path;

/// layers::frame_pattern, its error a HostError.
std::string frame_pattern(const std::string& text, std::string* range = nullptr);

/// "1-48", "1-48x2", "3,5,10-20": the frames, in order (layers::frame_list), each once.
/// Throws HostError naming `spec`.
std::vector<int> parse_frame_list(const std::string& spec);

/// The frames whose files exist under `pattern`, ascending; throws HostError naming the
/// pattern when none does.
std::vector<int> frames_on_disk(const std::string& text, const std::string& pattern);

/// One input pattern of a sequence run: the frames it has and the ones read so far. The
/// frames an operator asks for are read in parallel as far as the memory budget allows,
/// and kept while they are within reach of the frame being processed.
class FrameSequence {
public:
    FrameSequence(std::string pattern, std::vector<int> frames);

    const std::string& pattern() const { return pattern_; }
    const std::vector<int>& frames() const { return frames_; }

    /// The frames `offsets` positions away from `frame` in the frame list (null past either
    /// end), reading those not yet read with `options`. The first call compares the headers
    /// of every frame: one data window and one set of channels, or a LayerError naming the
    /// first frame that differs. Throws FileError for a file that cannot be read and
    /// HostError when the frames held would exceed the memory budget.
    std::vector<const OIIO::ImageBuf*> around(int frame, const std::vector<int>& offsets,
                                              const layers::ReadOptions& options);

    /// Keeps a copy of `image`, frame `frame` as read, so that it is not read again when
    /// it becomes a neighbour.
    void remember(int frame, const OIIO::ImageBuf& image);

    /// Drops the frames out of reach of `frame` (further than the widest request so far).
    void forget_beyond_reach(int frame);

private:
    int position(int frame) const;
    void check_frames_match(const layers::ReadOptions& options);
    void read_missing(const std::vector<int>& frames, const layers::ReadOptions& options);

    std::string pattern_;
    std::vector<int> frames_;
    int reach_ = 0;
    bool frames_checked_ = false;
    std::map<int, std::shared_ptr<OIIO::ImageBuf>> read_;
};

}  // namespace statmc::tool
