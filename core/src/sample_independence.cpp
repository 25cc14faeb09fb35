#include "statmc/core/sample_independence.h"

#include <cstring>
#include <stdexcept>

namespace statmc {

namespace {

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

bool identical_pixels(const std::vector<ConstPlane>& a, const std::vector<ConstPlane>& b,
                      int width, int height)
{
    if (a.size() != b.size())
        throw std::invalid_argument("identical_pixels: the images differ in channel count");
    for (std::size_t c = 0; c < a.size(); ++c)
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                if (!same_bits(a[c](x, y), b[c](x, y)))
                    return false;
    return true;
}

SharedNoise shared_noise(const StatisticsView& a, const StatisticsView& b)
{
    if (a.width != b.width || a.height != b.height || a.channels != b.channels)
        throw std::invalid_argument("shared_noise: the frames differ in size or channels");
    const bool plain = a.has_variance() && b.has_variance();
    if (!plain && !(a.has_box_cox() && b.has_box_cox()))
        throw std::invalid_argument("shared_noise: the frames have no variance in common");
    const auto& a_mean = plain ? a.mean : a.bc_mean;
    const auto& b_mean = plain ? b.mean : b.bc_mean;
    const auto& a_var = plain ? a.variance : a.bc_variance;
    const auto& b_var = plain ? b.variance : b.bc_variance;
    SharedNoise shared;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool noisy = false, same = true;
            for (int c = 0; c < a.channels; ++c) {
                noisy = noisy || a_var[c](x, y) > 0.f;
                same = same && same_bits(a_mean[c](x, y), b_mean[c](x, y)) &&
                       same_bits(a_var[c](x, y), b_var[c](x, y));
            }
            shared.noisy += noisy;
            shared.identical += noisy && same;
        }
    return shared;
}

}  // namespace statmc
