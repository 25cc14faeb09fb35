#include "dense_copies.h"

#include <cstddef>

#include <tbb/parallel_for.h>

namespace statmc::detail {

std::vector<ConstPlane> dense_copies(const std::vector<ConstPlane>& planes, int width, int height,
                                     std::vector<float>& storage)
{
    const std::size_t pixels = std::size_t(width) * height;
    storage.resize(pixels * planes.size());
    tbb::parallel_for(0, height, [&](int y) {
        const std::size_t row = std::size_t(y) * width;
        for (int x = 0; x < width; ++x)
            for (std::size_t k = 0; k < planes.size(); ++k)
                storage[k * pixels + row + x] = planes[k](x, y);
    });
    std::vector<ConstPlane> views;
    for (std::size_t k = 0; k < planes.size(); ++k)
        views.push_back(dense_plane(storage.data() + k * pixels, width));
    return views;
}

}  // namespace statmc::detail
