#include "statmc/compare/ssim.h"

#include <array>
#include <cmath>

namespace statmc {

namespace {

constexpr int kRadius = 5;  // 11×11 window
constexpr double kSigma = 1.5, kK1 = 0.01, kK2 = 0.03;

std::array<double, 2 * kRadius + 1> gaussian_taps()
{
    std::array<double, 2 * kRadius + 1> taps{};
    for (int i = -kRadius; i <= kRadius; ++i)
        taps[i + kRadius] = std::exp(-0.5 * i * i / (kSigma * kSigma));
    return taps;
}

// Windowed mean of `v` along one axis, the window truncated at the image edge and
// renormalized; the Gaussian is separable, so two passes give the 2-D window.
std::vector<double> blur_axis(const std::vector<double>& v, int w, int h, bool along_x)
{
    static const auto taps = gaussian_taps();
    std::vector<double> out(v.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0, weight = 0;
            for (int d = -kRadius; d <= kRadius; ++d) {
                const int xx = along_x ? x + d : x, yy = along_x ? y : y + d;
                if (xx < 0 || xx >= w || yy < 0 || yy >= h)
                    continue;
                sum += taps[d + kRadius] * v[std::size_t(yy) * w + xx];
                weight += taps[d + kRadius];
            }
            out[std::size_t(y) * w + x] = sum / weight;
        }
    return out;
}

std::vector<double> windowed_mean(const std::vector<double>& v, int w, int h)
{
    return blur_axis(blur_axis(v, w, h, true), w, h, false);
}

}  // namespace

double mean_ssim(const std::vector<float>& a, const std::vector<float>& b, int w, int h)
{
    const std::size_t n = std::size_t(w) * h;
    std::vector<double> x(a.begin(), a.end()), y(b.begin(), b.end()), xx(n), yy(n), xy(n);
    for (std::size_t i = 0; i < n; ++i) {
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    const auto mx = windowed_mean(x, w, h), my = windowed_mean(y, w, h);
    const auto mxx = windowed_mean(xx, w, h), myy = windowed_mean(yy, w, h),
               mxy = windowed_mean(xy, w, h);
    const double c1 = kK1 * kK1, c2 = kK2 * kK2;  // (K·L)² with L = 1
    double total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double vx = mxx[i] - mx[i] * mx[i], vy = myy[i] - my[i] * my[i];
        const double cov = mxy[i] - mx[i] * my[i];
        total += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) /
                 ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
    }
    return total / double(n);
}

}  // namespace statmc
