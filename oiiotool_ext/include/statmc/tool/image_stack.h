// oiiotool's image stack: inputs are pushed, commands pop their operands and push
// results, -o writes the top.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

namespace statmc::tool {

struct StackImage {
    OIIO::ImageBuf image;
    std::string label;  ///< names the image in messages: its file, or the command that made it
};

class ImageStack {
public:
    void push(StackImage image) { images_.push_back(std::move(image)); }
    std::size_t size() const { return images_.size(); }
    bool empty() const { return images_.empty(); }

    /// The top image; throws ToolError "<command>: the image stack is empty".
    const StackImage& top(const std::string& command) const;
    StackImage pop(const std::string& command);
    /// The top n images, bottom first; throws ToolError when fewer are stacked.
    std::vector<StackImage> pop(std::size_t n, const std::string& command);

private:
    std::vector<StackImage> images_;
};

}  // namespace statmc::tool
