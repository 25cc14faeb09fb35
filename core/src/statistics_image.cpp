#include "statmc/core/statistics_image.h"

#include <string>

#include <tbb/parallel_for.h>

#include "statmc/core/thread_limit.h"

namespace statmc {

StatisticsView StatisticsPlanes::view() const
{
    StatisticsView v;
    v.width = width;
    v.height = height;
    v.channels = channels;
    const std::size_t n = std::size_t(width) * height;
    v.count = dense_plane(count.data(), width);
    // An empty vector (e.g. no Box-Cox planes) gives null planes.
    auto plane = [&](const std::vector<float>& v, int c) {
        return v.empty() ? ConstPlane{} : dense_plane(v.data() + c * n, width);
    };
    for (int c = 0; c < channels; ++c) {
        v.mean[c] = plane(mean, c);
        v.variance[c] = plane(variance, c);
        v.bc_mean[c] = plane(bc_mean, c);
        v.bc_variance[c] = plane(bc_variance, c);
        v.bc_moment3[c] = plane(bc_moment3, c);
        v.moment3[c] = plane(moment3, c);
        v.moment4[c] = plane(moment4, c);
        v.bc_moment4[c] = plane(bc_moment4, c);
    }
    return v;
}

template <int C>
StatisticsPlanes StatisticsImage<C>::planes() const
{
    StatisticsPlanes p;
    p.width = width_;
    p.height = height_;
    p.channels = C;
    const std::size_t n = pixels_.size();
    p.count.resize(n);
    for (auto* plane : {&p.mean, &p.variance, &p.bc_mean, &p.bc_variance, &p.bc_moment3, &p.moment3,
                        &p.moment4, &p.bc_moment4})
        plane->resize(n * C);
    for (std::size_t i = 0; i < n; ++i) {
        const Pixel& px = pixels_[i];
        p.count[i] = float(px.n);
        // s² is undefined below two samples; 0 is stored and the count tells the reader.
        const double to_variance = px.n > 1 ? 1.0 / (px.n - 1) : 0.0;
        const double per_sample = px.n > 0 ? 1.0 / px.n : 0.0;
        for (int c = 0; c < C; ++c) {
            const std::size_t k = c * n + i;
            p.mean[k] = float(px.raw[c].mean);
            p.variance[k] = float(px.raw[c].m2 * to_variance);
            p.bc_mean[k] = float(px.box_cox[c].mean);
            p.bc_variance[k] = float(px.box_cox[c].m2 * to_variance);
            p.bc_moment3[k] = float(px.box_cox[c].m3 * per_sample);
            p.moment3[k] = float(px.raw[c].m3 * per_sample);
            p.moment4[k] = float(px.raw[c].m4 * per_sample);
            p.bc_moment4[k] = float(px.box_cox[c].m4 * per_sample);
        }
    }
    return p;
}

namespace {

template <int C>
void require_mergeable(const StatisticsView& view, const char* caller)
{
    if (view.channels != C)
        throw std::invalid_argument(std::string(caller) + ": channel count differs");
    if (!view.count || !view.has_box_cox())
        throw std::invalid_argument(std::string(caller) + ": Box-Cox planes are missing");
}

}  // namespace

template <int C>
PixelMoments<C, double> stored_pixel(const StatisticsView& view, int x, int y)
{
    auto at = [x, y](const ConstPlane& plane) { return plane ? double(plane(x, y)) : 0.0; };
    PixelMoments<C, double> px;
    px.n = view.count(x, y);
    const double to_mean_variance = view.variance_of_mean ? px.n : 1.0;
    const double m2_scale = px.n > 1 ? px.n - 1 : 0.0;
    for (int c = 0; c < C; ++c) {
        px.raw[c].mean = view.mean[c](x, y);
        px.raw[c].m2 = at(view.variance[c]) * to_mean_variance * m2_scale;
        px.raw[c].m3 = at(view.moment3[c]) * px.n;
        px.raw[c].m4 = at(view.moment4[c]) * px.n;
        px.box_cox[c].mean = at(view.bc_mean[c]);
        px.box_cox[c].m2 = at(view.bc_variance[c]) * m2_scale;
        px.box_cox[c].m3 = at(view.bc_moment3[c]) * px.n;
        px.box_cox[c].m4 = at(view.bc_moment4[c]) * px.n;
    }
    return px;
}

StatisticsView with_stand_in_box_cox(StatisticsView view, const ConstPlane& zero)
{
    for (int c = 0; c < view.channels; ++c)
        if (!view.bc_mean[c] || !view.bc_variance[c] || !view.bc_moment3[c]) {
            view.bc_mean[c] = view.mean[c];
            view.bc_variance[c] = view.variance[c];
            view.bc_moment3[c] = zero;
        }
    return view;
}

template <int C>
StatisticsImage<C> StatisticsImage<C>::from_view(const StatisticsView& view)
{
    require_mergeable<C>(view, "StatisticsImage::from_view");
    StatisticsImage img(view.width, view.height);
    for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x)
            img.at(x, y) = stored_pixel<C>(view, x, y);
    return img;
}

template <int C>
StatisticsImage<C> StatisticsImage<C>::merged(const std::vector<StatisticsView>& views,
                                              int nthreads)
{
    if (views.empty())
        throw std::invalid_argument("StatisticsImage::merged: no views");
    for (const StatisticsView& v : views) {
        require_mergeable<C>(v, "StatisticsImage::merged");
        if (v.width != views[0].width || v.height != views[0].height)
            throw std::invalid_argument("StatisticsImage::merged: resolutions differ");
    }
    StatisticsImage img(views[0].width, views[0].height);
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, img.height_, [&](int y) {
            for (int x = 0; x < img.width_; ++x) {
                Pixel px = stored_pixel<C>(views[0], x, y);
                for (std::size_t k = 1; k < views.size(); ++k)
                    px.merge(stored_pixel<C>(views[k], x, y));
                img.at(x, y) = px;
            }
        });
    });
    return img;
}

#define STATMC_STORED(C)                                                                           \
    template PixelMoments<C, double> stored_pixel<C>(const StatisticsView&, int, int);             \
    template class StatisticsImage<C>;
STATMC_STORED(1)
STATMC_STORED(3)
STATMC_STORED(4)
#undef STATMC_STORED

}  // namespace statmc
