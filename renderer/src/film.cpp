#include "statmc/render/film.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <unistd.h>

namespace statmc::render {

Film::Film(int w, int h, BounceLayout steering_layout, BounceLayout layers)
    : width(w), height(h), stats(w, h), albedo_sum(std::size_t(w) * h * 3),
      normal_sum(std::size_t(w) * h * 3), depth_sum(std::size_t(w) * h),
      albedo_squares(std::size_t(w) * h), normal_squares(std::size_t(w) * h)
{
    if (!steering_layout.empty())
        steering = std::make_unique<SteeringStatistics>(w, h, steering_layout);
    if (!layers.empty())
        bounces = std::make_unique<BounceStatistics>(w, h, layers);
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

// Σ_c s²_c = (Σ|g|² − n·Σ_c mean_c²)/(n − 1), from the sums of a 3-channel guide.
std::vector<float> summed_variance(const std::vector<double>& sums,
                                   const std::vector<double>& squares, const Film& film)
{
    const std::size_t n = std::size_t(film.width) * film.height;
    std::vector<float> out(n);
    for (int y = 0; y < film.height; ++y)
        for (int x = 0; x < film.width; ++x) {
            const std::size_t i = std::size_t(y) * film.width + x;
            const double count = film.stats.at(x, y).n;
            if (count < 2)
                continue;
            double mean_squares = 0;
            for (int c = 0; c < 3; ++c)
                mean_squares += sums[c * n + i] * sums[c * n + i] / count;
            out[i] = float(std::max(0.0, (squares[i] - mean_squares) / (count - 1)));
        }
    return out;
}

}  // namespace

std::vector<float> Film::albedo_variance() const
{
    return summed_variance(albedo_sum, albedo_squares, *this);
}
std::vector<float> Film::normal_variance() const
{
    return summed_variance(normal_sum, normal_squares, *this);
}

std::vector<float> Film::albedo() const { return average(albedo_sum, 3, *this); }
std::vector<float> Film::normal() const { return average(normal_sum, 3, *this); }
std::vector<float> Film::depth() const { return average(depth_sum, 1, *this); }
std::vector<float> Film::motion() const
{
    return motion_sum.empty() ? std::vector<float>{} : average(motion_sum, 2, *this);
}

Film::SampleCounts Film::sample_counts() const
{
    SampleCounts counts;
    double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double n = stats.at(x, y).n;
            sum += n;
            lo = std::min(lo, n);
            hi = std::max(hi, n);
        }
    counts.min = int(lo);
    counts.max = int(hi);
    counts.mean = sum / (double(width) * height);
    counts.uniform = lo == hi;
    return counts;
}

double Film::bytes_needed(int width, int height, const BounceLayout& steering,
                          const BounceLayout& layers)
{
    using Stats3 = StatisticsImage<3>;
    using Stats4 = StatisticsImage<BounceStatistics::kGroup>;
    const int groups =
        (layers.quantities() + BounceStatistics::kGroup - 1) / BounceStatistics::kGroup;
    // Every accumulated double, the estimates' floats, and the output's float planes (at
    // most one of each per statistic and channel, written once).
    const double per_pixel =
        sizeof(Stats3::Pixel) + 9 * sizeof(double) +
        (steering.empty()
             ? 0.0
             : sizeof(double) + steering.quantities() *
                                    (sizeof(SteeringStatistics::Moments) + 6.0 * sizeof(float))) +
        groups * (sizeof(Stats4::Pixel) + 16 * 4.0 * sizeof(float)) + 64 * sizeof(float);
    return double(width) * double(height) * per_pixel;
}

void require_renderable_resolution(int width, int height, const BounceLayout& steering,
                                   const BounceLayout& layers, const std::string& source)
{
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        throw std::runtime_error(source + ": width and height must be in 1..65536, got " +
                                 std::to_string(width) + "x" + std::to_string(height));
    const double memory_limit =
        0.75 * double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
    const double needed = Film::bytes_needed(width, height, steering, layers);
    if (needed > memory_limit) {
        char text[160];
        std::snprintf(text, sizeof text,
                      ": %dx%d needs about %.1f GB for the film, more than the %.1f GB allowed "
                      "(three quarters of this machine's memory)",
                      width, height, needed / 1e9, memory_limit / 1e9);
        throw std::runtime_error(source + text);
    }
}

}  // namespace statmc::render
