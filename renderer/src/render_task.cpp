#include "statmc/render/render_task.h"

#include <charconv>
#include <cstdint>
#include <stdexcept>

namespace statmc::render {

RenderTask parse_task(const std::string& text, const std::string& option)
{
    RenderTask task;
    const char* end = text.data() + text.size();
    const auto i = std::from_chars(text.data(), end, task.index);
    const bool shaped = i.ec == std::errc() && i.ptr != text.data() && i.ptr != end &&
                        *i.ptr == '/';
    const auto n = shaped ? std::from_chars(i.ptr + 1, end, task.count) : i;
    if (!shaped || n.ec != std::errc() || n.ptr != end || n.ptr == i.ptr + 1)
        throw std::runtime_error(option + ": expected I/N (task I of N, counted from 0), got '" +
                                 text + "'");
    if (task.count < 1)
        throw std::runtime_error(option + " " + text + ": the task count must be at least 1");
    if (task.index < 0 || task.index >= task.count)
        throw std::runtime_error(option + " " + text + ": task index " +
                                 std::to_string(task.index) + " is not in 0.." +
                                 std::to_string(task.count - 1) + " (tasks count from 0)");
    return task;
}

layers::SampleRange task_samples(int total_spp, const RenderTask& task)
{
    auto bound = [&](int i) {
        return int(std::int64_t(i) * total_spp / task.count);
    };
    if (task.count > total_spp)
        throw std::runtime_error(std::to_string(total_spp) + " samples per pixel split over " +
                                 std::to_string(task.count) +
                                 " tasks would leave some tasks none: use at most as many tasks "
                                 "as samples per pixel");
    return {bound(task.index), bound(task.index + 1)};
}

}  // namespace statmc::render
