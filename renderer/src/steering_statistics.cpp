#include "statmc/render/steering_statistics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "statmc/core/box_cox.h"
#include "statmc/core/estimator_image.h"
#include "statmc/core/filter.h"
#include "statmc/core/statistics_image.h"

namespace statmc::render {

SteeringStatistics::SteeringStatistics(int width, int height, BounceLayout layout)
    : width_(width), height_(height), layout_(layout),
      count_(std::size_t(width) * std::size_t(height)),
      moments_(count_.size() * std::size_t(layout.quantities()))
{
    if (layout.quantities() <= 0)
        throw std::invalid_argument("SteeringStatistics: nothing to track");
}

void SteeringStatistics::add(int x, int y, const float* values)
{
    const std::size_t pixel = std::size_t(y) * std::size_t(width_) + std::size_t(x);
    const int q_total = layout_.quantities();
    const double n = count_[pixel], n1 = n + 1;
    Moments* m = moments_.data() + pixel * std::size_t(q_total);
    for (int q = 0; q < q_total; ++q) {
        const float v = values[q];
        const double value = std::isfinite(v) && v >= -1e-5f ? double(v) : 0.0;
        // CentralMoments::add, term for term, up to the third moment.
        m[q].mean += (value - m[q].mean) / n1;
        const double delta = box_cox(value) - m[q].bc_mean;
        const double delta_n = delta / n1;
        const double term = delta * delta_n * n;
        m[q].bc_mean += delta_n;
        m[q].bc_m3 += term * delta_n * (n1 - 2) - 3 * delta_n * m[q].bc_m2;
        m[q].bc_m2 += term;
    }
    count_[pixel] = n1;
}

BounceEstimates SteeringStatistics::denoise(const DenoiseOptions& options, int threads) const
{
    const int q_total = layout_.quantities();
    const std::size_t npix = count_.size();
    BounceEstimates est{layout_, std::vector<float>(npix * std::size_t(q_total))};
    StatisticsPlanes planes;
    planes.width = width_;
    planes.height = height_;
    planes.count.resize(npix);
    for (std::size_t i = 0; i < npix; ++i)
        planes.count[i] = float(count_[i]);
    for (int first = 0; first < q_total; first += BounceStatistics::kGroup) {
        const int channels = std::min(BounceStatistics::kGroup, q_total - first);
        planes.channels = channels;
        for (auto* plane : {&planes.mean, &planes.bc_mean, &planes.bc_variance, &planes.bc_moment3})
            plane->resize(npix * std::size_t(channels));
        // As StatisticsImage::planes() converts them: s² = M2/(n − 1), m3 = M3/n.
        for (std::size_t i = 0; i < npix; ++i) {
            const double n = count_[i];
            const double to_variance = n > 1 ? 1.0 / (n - 1) : 0.0;
            const double per_sample = n > 0 ? 1.0 / n : 0.0;
            for (int c = 0; c < channels; ++c) {
                const Moments& m = moments_[i * std::size_t(q_total) + std::size_t(first + c)];
                const std::size_t k = std::size_t(c) * npix + i;
                planes.mean[k] = float(m.mean);
                planes.bc_mean[k] = float(m.bc_mean);
                planes.bc_variance[k] = float(m.bc_m2 * to_variance);
                planes.bc_moment3[k] = float(m.bc_m3 * per_sample);
            }
        }
        const EstimatorImage e = estimators_from_statistics(planes.view(), TestDomain::BoxCox);
        // The filter writes each channel straight into its slot of the pixel-major values.
        std::vector<Plane> out;
        for (int c = 0; c < channels; ++c)
            out.push_back(
                Plane{est.values.data() + first + c, q_total, std::ptrdiff_t(width_) * q_total});
        filter(e, Guides{}, options, out, {}, threads);
    }
    return est;
}

}  // namespace statmc::render
