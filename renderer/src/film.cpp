#include "statmc/render/film.h"

#include <algorithm>
#include <limits>

namespace statmc::render {

Film::Film(int w, int h, BounceLayout bounce_layout)
    : width(w), height(h), stats(w, h, /*track_positions=*/true),
      albedo_sum(std::size_t(w) * h * 3), normal_sum(std::size_t(w) * h * 3),
      depth_sum(std::size_t(w) * h)
{
    if (!bounce_layout.empty())
        bounces = std::make_unique<BounceStatistics>(w, h, bounce_layout);
}

namespace {

std::vector<float> average(const std::vector<double>& sums, int channels, const Film& film)
{
    const std::size_t n = std::size_t(film.width) * film.height;
    std::vector<float> out(n * channels);
    for (int y = 0; y < film.height; ++y)
        for (int x = 0; x < film.width; ++x) {
            const std::size_t i = std::size_t(y) * film.width + x;
            const double count = film.stats.at(x, y).n;
            for (int c = 0; c < channels; ++c)
                out[c * n + i] = count > 0 ? float(sums[c * n + i] / count) : 0.f;
        }
    return out;
}

}  // namespace

std::vector<float> Film::albedo() const { return average(albedo_sum, 3, *this); }
std::vector<float> Film::normal() const { return average(normal_sum, 3, *this); }
std::vector<float> Film::depth() const { return average(depth_sum, 1, *this); }

int Film::min_samples() const
{
    double m = std::numeric_limits<double>::infinity();
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            m = std::min(m, stats.at(x, y).n);
    return int(m);
}

}  // namespace statmc::render
