// oiiotool's image stack: inputs are pushed, commands pop their operands and push
// results, -o writes the top.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "frame_sequence.h"
#include "statmc/layers/exr_files.h"

namespace statmc::tool {

/// One stack entry: an image with one or more subimages (the parts of a multi-part EXR),
/// as oiiotool's stack holds them.
struct StackImage {
    StackImage() = default;
    // Moved, not copied through an initializer list: a copy of a failed ImageBuf is
    // not safe in OIIO 2.4 and would lose the error.
    StackImage(OIIO::ImageBuf image, std::string name) : label(std::move(name))
    {
        subimages.push_back(std::move(image));
    }
    StackImage(std::vector<OIIO::ImageBuf> images, std::string name)
        : subimages(std::move(images)), label(std::move(name))
    {
    }

    std::vector<OIIO::ImageBuf> subimages;  ///< never empty
    std::string label;  ///< names the image in messages: its file, or the command that made it
    /// The coarser MIP levels of each subimage as read (empty, or one entry per subimage):
    /// a copy writes them back. Results of operators are single-level images.
    layers::MipLevels mip_levels;
    /// Set when the image is frame `frame` of `sequence` exactly as read (-i of a frame
    /// pattern): what an operator looking across frames reads the others from. A command
    /// that changes the image drops it.
    std::shared_ptr<FrameSequence> sequence;
    int frame = 0;

    /// Subimage 0: what a command reads unless -a is given.
    const OIIO::ImageBuf& image() const { return subimages.front(); }
};

class ImageStack {
public:
    void push(StackImage image) { images_.push_back(std::move(image)); }
    std::size_t size() const { return images_.size(); }
    bool empty() const { return images_.empty(); }

    /// The top image; throws HostError "<command>: the image stack is empty".
    const StackImage& top(const std::string& command) const;
    StackImage pop(const std::string& command);
    /// The top n images, bottom first; throws HostError when fewer are stacked ("the image
    /// stack is empty" when none are and n > 0).
    std::vector<StackImage> pop(std::size_t n, const std::string& command);

private:
    std::vector<StackImage> images_;
};

}  // namespace statmc::tool
