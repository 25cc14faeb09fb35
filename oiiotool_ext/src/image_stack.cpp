#include "image_stack.h"

#include "statmc/plugin_host/host_error.h"

namespace statmc::tool {

const StackImage& ImageStack::top(const std::string& command) const
{
    if (images_.empty())
        throw host::HostError(command + ": the image stack is empty (give an input image first)");
    return images_.back();
}

StackImage ImageStack::pop(const std::string& command)
{
    top(command);
    StackImage image = std::move(images_.back());
    images_.pop_back();
    return image;
}

std::vector<StackImage> ImageStack::pop(std::size_t n, const std::string& command)
{
    if (n > 0)
        top(command);  // "the image stack is empty" says more than "needs 1"
    if (n > images_.size())
        throw host::HostError(command + ": needs " + std::to_string(n) +
                              " images, the stack holds " + std::to_string(images_.size()));
    std::vector<StackImage> popped(std::make_move_iterator(images_.end() - n),
                                   std::make_move_iterator(images_.end()));
    images_.erase(images_.end() - n, images_.end());
    return popped;
}

}  // namespace statmc::tool
