#include "statmc/core/explained_variance.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/fisher_f.hpp>
#include <tbb/parallel_for.h>

#include "statmc/core/plane.h"
#include "statmc/core/thread_limit.h"

namespace statmc {

namespace {

// F(2, df) critical values for df = 1..kExactLimit; above it the last one, which is at most
// 0.2% above the limit χ²₂/2 and so errs towards leaving a variance alone.
constexpr int kExactLimit = 1024;

std::vector<double> f_critical_values(double alpha)
{
    std::vector<double> f(kExactLimit + 1, 0.0);
    for (int df = 1; df <= kExactLimit; ++df)
        f[df] = boost::math::quantile(
            boost::math::complement(boost::math::fisher_f_distribution<double>(2, df), alpha));
    return f;
}

// The planes of one domain: the variance with its higher moments and co-moments.
struct Domain {
    const std::array<ConstPlane, 4>* variance;
    const std::array<ConstPlane, 4>* moment3;
    const std::array<ConstPlane, 4>* moment4;
    const std::array<ConstPlane, 4>* cov_u;
    const std::array<ConstPlane, 4>* cov_v;
    std::vector<float>* out_variance;
    std::vector<float>* out_moment3;
    std::vector<float>* out_moment4;
};

bool all_present(const std::array<ConstPlane, 4>& planes, int channels)
{
    for (int c = 0; c < channels; ++c)
        if (!planes[c])
            return false;
    return true;
}

std::size_t correct_domain(const StatisticsView& view, const Domain& d,
                           const std::vector<double>& f_critical)
{
    const std::size_t pixels = std::size_t(view.width) * view.height;
    const bool third = all_present(*d.moment3, view.channels);
    const bool fourth = all_present(*d.moment4, view.channels);
    d.out_variance->resize(pixels * view.channels);
    if (third)
        d.out_moment3->resize(pixels * view.channels);
    if (fourth)
        d.out_moment4->resize(pixels * view.channels);
    std::vector<std::size_t> corrected(view.height, 0);
    tbb::parallel_for(0, view.height, [&](int y) {
        for (int x = 0; x < view.width; ++x) {
            const double n = view.count(x, y);
            const double suu = view.subpixel_uu(x, y), svv = view.subpixel_vv(x, y),
                         suv = view.subpixel_uv(x, y);
            for (int c = 0; c < view.channels; ++c) {
                const std::size_t k = std::size_t(c) * pixels + std::size_t(y) * view.width + x;
                const double s2 = (*d.variance)[c](x, y);
                double ratio = 1.0;
                if (n >= 4 && s2 > 0 && std::isfinite(s2)) {
                    const double m2 = s2 * (n - 1) / n;
                    const double rss = residual_second_moment(m2, (*d.cov_u)[c](x, y),
                                                              (*d.cov_v)[c](x, y), suu, svv, suv);
                    const double df = n - 3;
                    const double critical = f_critical[std::min<int>(int(df), kExactLimit)];
                    // F = (explained / 2) / (residual / (n − 3)), written without dividing.
                    if (rss >= 0 && (m2 - rss) * df > 2 * critical * rss) {
                        ratio = std::max(rss * n / df, 0.0) / s2;
                        ++corrected[y];
                    }
                }
                (*d.out_variance)[k] = float(s2 * ratio);
                if (third)
                    (*d.out_moment3)[k] = float((*d.moment3)[c](x, y) * ratio * std::sqrt(ratio));
                if (fourth)
                    (*d.out_moment4)[k] = float((*d.moment4)[c](x, y) * ratio * ratio);
            }
        }
    });
    std::size_t total = 0;
    for (std::size_t k : corrected)
        total += k;
    return total;
}

void use_dense(std::array<ConstPlane, 4>& planes, const std::vector<float>& data, int channels,
               int width, std::size_t pixels)
{
    if (data.empty())
        return;
    for (int c = 0; c < channels; ++c)
        planes[c] = dense_plane(data.data() + c * pixels, width);
}

}  // namespace

double residual_second_moment(double m2, double cu, double cv, double suu, double svv, double suv)
{
    const double det = suu * svv - suv * suv;
    // A singular S (all samples on one line, or one position) has no plane to remove.
    if (!(suu > 0 && svv > 0 && det > 1e-9 * suu * svv))
        return -1.0;
    const double explained = (svv * cu * cu - 2 * suv * cu * cv + suu * cv * cv) / det;
    return std::max(m2 - explained, 0.0);
}

StatisticsView ExplainedVariance::applied_to(StatisticsView view) const
{
    const std::size_t pixels = std::size_t(view.width) * view.height;
    use_dense(view.variance, variance, view.channels, view.width, pixels);
    use_dense(view.moment3, moment3, view.channels, view.width, pixels);
    use_dense(view.moment4, moment4, view.channels, view.width, pixels);
    use_dense(view.bc_variance, bc_variance, view.channels, view.width, pixels);
    use_dense(view.bc_moment3, bc_moment3, view.channels, view.width, pixels);
    use_dense(view.bc_moment4, bc_moment4, view.channels, view.width, pixels);
    return view;
}

ExplainedVariance remove_explained_variance(const StatisticsView& view,
                                            const ExplainedVarianceOptions& options, int nthreads)
{
    if (!view.has_positions())
        throw std::invalid_argument(
            "remove_explained_variance: the statistics carry no position co-moments");
    if (view.variance_of_mean)
        throw std::invalid_argument(
            "remove_explained_variance: needs per-sample variances, not variances of the mean");
    if (!(options.alpha > 0 && options.alpha < 1))
        throw std::invalid_argument("remove_explained_variance: alpha must be in (0, 1)");
    const std::vector<double> f_critical = f_critical_values(options.alpha);
    ExplainedVariance out;
    run_with_threads(nthreads, [&] {
        if (all_present(view.variance, view.channels))
            out.corrected_pixels +=
                correct_domain(view,
                               {&view.variance, &view.moment3, &view.moment4, &view.cov_u,
                                &view.cov_v, &out.variance, &out.moment3, &out.moment4},
                               f_critical);
        if (view.has_box_cox_positions())
            out.corrected_pixels += correct_domain(
                view,
                {&view.bc_variance, &view.bc_moment3, &view.bc_moment4, &view.bc_cov_u,
                 &view.bc_cov_v, &out.bc_variance, &out.bc_moment3, &out.bc_moment4},
                f_critical);
    });
    return out;
}

}  // namespace statmc
