#include "statmc/core/temporal_merge.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "statmc/core/critical_values.h"
#include "statmc/core/firefly_guard.h"
#include "statmc/core/thread_limit.h"

namespace statmc {

std::string TemporalOptions::validate() const
{
    if (frames < 0)
        return "temporal must be ≥ 0, got " + std::to_string(frames);
    if (radius < 0)
        return "temporal_radius must be ≥ 0, got " + std::to_string(radius);
    return "";
}

namespace {

bool inside(const StatisticsView& v, int x, int y)
{
    return x >= 0 && y >= 0 && x < v.width && y < v.height;
}

// A motion vector rounded to whole pixels; false when it is not finite or absurdly long.
bool rounded_motion(const TemporalFrame& f, int x, int y, int& mx, int& my)
{
    const float fx = f.motion_x(x, y), fy = f.motion_y(x, y);
    const float limit = 4.f * float(f.stats.width + f.stats.height);
    if (!(std::abs(fx) <= limit && std::abs(fy) <= limit))
        return false;
    mx = int(std::lround(fx));
    my = int(std::lround(fy));
    return true;
}

// One frame back: frame f's motion points from (x, y) to where it was in frame f − 1.
bool step_back(const TemporalFrame& f, int& x, int& y)
{
    int mx, my;
    if (!rounded_motion(f, x, y, mx, my))
        return false;
    x += mx;
    y += my;
    return inside(f.stats, x, y);
}

// One frame forward, from frame f − 1 to frame f: the pixel q of f whose motion leads back
// to (x, y). Frame f − 1's own motion at (x, y), reversed, is the first guess (constant
// velocity); two fixed-point steps refine it, and q counts only if it lands exactly back.
bool step_forward(const TemporalFrame& previous, const TemporalFrame& f, int& x, int& y)
{
    int qx = x, qy = y, mx = 0, my = 0;
    if (previous.has_motion() && rounded_motion(previous, x, y, mx, my)) {
        qx = x - mx;
        qy = y - my;
    }
    for (int step = 0; step < 2; ++step) {
        if (!inside(f.stats, qx, qy) || !rounded_motion(f, qx, qy, mx, my))
            return false;
        qx = x - mx;
        qy = y - my;
    }
    if (!inside(f.stats, qx, qy) || !rounded_motion(f, qx, qy, mx, my) || qx + mx != x ||
        qy + my != y)
        return false;
    x = qx;
    y = qy;
    return true;
}

void check_frames(const std::vector<TemporalFrame>& frames, int centre, TestDomain domain)
{
    if (centre < 0 || centre >= int(frames.size()))
        throw std::invalid_argument("temporal merge: the centre frame is not among the frames");
    const StatisticsView& c = frames[centre].stats;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const StatisticsView& v = frames[k].stats;
        if (v.width != c.width || v.height != c.height || v.channels != c.channels)
            throw std::invalid_argument("temporal merge: frame " + std::to_string(k) +
                                        " differs from the centre in resolution or channels");
        if (frames[k].has_motion() != frames[centre].has_motion())
            throw std::invalid_argument(
                "temporal merge: some frames have motion layers and others do not");
        if (domain == TestDomain::BoxCox && !v.has_box_cox())
            throw std::invalid_argument("temporal merge: frame " + std::to_string(k) +
                                        " lacks the Box-Cox planes the test reads");
        if (domain == TestDomain::Untransformed && !(v.count && v.variance[0]))
            throw std::invalid_argument("temporal merge: frame " + std::to_string(k) +
                                        " lacks the variance the test reads");
        // A moment one frame lacks would be merged as 0 into the others'.
        if (v.has_box_cox() != c.has_box_cox() || v.has_moments() != c.has_moments() ||
            v.has_box_cox_moment4() != c.has_box_cox_moment4())
            throw std::invalid_argument("temporal merge: frame " + std::to_string(k) +
                                        " has other statistics than the centre");
    }
}

// The firefly guard for a temporal member: the largest noise level the centre accepts from
// another frame. A member is the same pixel seen again, so its level is compared with the
// centre's own (when it has one), not with the larger of its own and its neighbourhood's
// that spatial members face: a pixel beside a light whose edge moves by a fraction of a
// pixel between frames sees, in another frame, the light straddling it (mean and variance
// up a hundredfold), and the symmetric test alone lets that in. A centre with no noise
// keeps the spatial rule (a black one in a sparsely lit region still takes any level).
float temporal_noise_limit(const NoiseLevels& noise, std::size_t pixel, float ratio)
{
    const float own = noise.level[pixel];
    return ratio > 0 && own > 0 ? std::min(noise.limit[pixel], ratio * own) : noise.limit[pixel];
}

// Each frame's estimators and firefly levels, computed once and shared by every pixel.
struct FrameTests {
    EstimatorImage est;
    NoiseLevels noise;
};

template <int C>
StatisticsPlanes merge_members(const std::vector<TemporalFrame>& frames, int centre,
                               TestDomain domain, const TemporalOptions& temporal,
                               const DenoiseOptions& filter, int nthreads, Plane members)
{
    const StatisticsView& cv = frames[centre].stats;
    const int w = cv.width, h = cv.height;
    // Merging needs Box-Cox planes; without them the untransformed ones stand in.
    const std::vector<float> zeros(std::size_t(w) * h, 0.f);
    const bool box_cox = cv.has_box_cox();
    std::vector<StatisticsView> views;
    for (const TemporalFrame& f : frames)
        views.push_back(box_cox ? f.stats
                                : with_stand_in_box_cox(f.stats, dense_plane(zeros.data(), w)));

    std::vector<FrameTests> tests(frames.size());
    float max_count = 2;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        if (std::abs(int(k) - centre) > temporal.frames)
            continue;  // out of reach: never a candidate
        tests[k].est = estimators_from_statistics(frames[k].stats, domain);
        tests[k].noise = noise_levels(tests[k].est, filter.firefly_ratio);
        for (float n : tests[k].est.count)
            if (std::isfinite(n))
                max_count = std::max(max_count, n);
    }
    const auto table = CriticalValues::shared(filter.alpha, 2.0 * std::floor(max_count) - 2.0);
    const CriticalValues& critical = *table;
    const EstimatorImage& ce = tests[centre].est;
    auto gamma2 = [&](const EstimatorImage& e, int x, int y) {
        const double g = critical.gamma(2.0 * std::floor(e.count[e.index(0, x, y)]) - 2.0);
        return g * g;
    };
    const int r = temporal.radius;

    StatisticsImage<C> out(w, h);
    run_with_threads(nthreads, [&] {
        tbb::parallel_for(0, h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                PixelMoments<C, double> px = stored_pixel<C>(views[centre], x, y);
                int joined = 0;
                const bool testable = ce.testable(x, y);
                const double gi = testable ? gamma2(ce, x, y) : 0.0;
                const float limit = temporal_noise_limit(
                    tests[centre].noise, std::size_t(y) * w + x, filter.firefly_ratio);
                for (int k = 0; k < int(frames.size()) && testable; ++k) {
                    int ox, oy;
                    if (std::abs(k - centre) > temporal.frames ||
                        !corresponding_pixel(frames, centre, k, x, y, ox, oy))
                        continue;
                    const EstimatorImage& e = tests[k].est;
                    for (int dy = -r; dy <= r; ++dy)
                        for (int dx = -r; dx <= r; ++dx) {
                            const int u = ox + dx, v = oy + dy;
                            if (dx * dx + dy * dy > r * r || !inside(cv, u, v) || !e.testable(u, v))
                                continue;
                            if (!(tests[k].noise.level[std::size_t(v) * w + u] <= limit))
                                continue;
                            const double gj = gamma2(e, u, v);
                            bool member = true;
                            for (int c = 0; c < C && member; ++c) {
                                const double d = double(ce.test_mean[ce.index(c, x, y)]) -
                                                 e.test_mean[e.index(c, u, v)];
                                member = d * d <= gi * ce.test_variance[ce.index(c, x, y)] +
                                                      gj * e.test_variance[e.index(c, u, v)];
                            }
                            if (!member)
                                continue;
                            px.merge(stored_pixel<C>(views[k], u, v));
                            ++joined;
                        }
                }
                out.at(x, y) = px;
                if (members)
                    members(x, y) = float(joined);
            }
        });
    });
    StatisticsPlanes planes = out.planes();
    if (!box_cox)
        planes.bc_mean.clear(), planes.bc_variance.clear(), planes.bc_moment3.clear(),
            planes.bc_moment4.clear();
    if (!cv.has_moments())
        planes.moment3.clear(), planes.moment4.clear();
    if (!cv.has_box_cox_moment4())
        planes.bc_moment4.clear();
    return planes;
}

}  // namespace

bool corresponding_pixel(const std::vector<TemporalFrame>& frames, int centre, int other, int x,
                         int y, int& ox, int& oy)
{
    if (other == centre || other < 0 || other >= int(frames.size()))
        return false;
    if (frames[centre].has_motion()) {
        for (int f = centre; f > other; --f)
            if (!step_back(frames[f], x, y))
                return false;
        for (int f = centre + 1; f <= other; ++f)
            if (!step_forward(frames[f - 1], frames[f], x, y))
                return false;
    }
    ox = x;
    oy = y;
    return true;
}

StatisticsPlanes merge_temporal_members(const std::vector<TemporalFrame>& frames, int centre,
                                        TestDomain domain, const TemporalOptions& temporal,
                                        const DenoiseOptions& filter, int nthreads, Plane members)
{
    if (const std::string why = temporal.validate(); !why.empty())
        throw std::invalid_argument(why);
    if (const std::string why = filter.validate(); !why.empty())
        throw std::invalid_argument(why);
    check_frames(frames, centre, domain);
    switch (frames[centre].stats.channels) {
    case 1:
        return merge_members<1>(frames, centre, domain, temporal, filter, nthreads, members);
    case 3:
        return merge_members<3>(frames, centre, domain, temporal, filter, nthreads, members);
    case 4:
        return merge_members<4>(frames, centre, domain, temporal, filter, nthreads, members);
    default:
        throw std::invalid_argument("temporal merge: statistics of 1, 3 or 4 channels only");
    }
}

}  // namespace statmc
