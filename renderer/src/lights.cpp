#include "statmc/render/lights.h"

#include <algorithm>
#include <cmath>

namespace statmc::render {

float Emitter::area() const
{
    if (kind == Kind::Triangle)
        return 0.5f * length(cross(p1 - p0, p2 - p0));
    return 4 * kPi * radius * radius;
}

Rgb Emitter::emitted(Vec3 n, Vec3 w) const { return two_sided || dot(n, w) > 0 ? radiance : Rgb{}; }

int Lights::add(const Emitter& e)
{
    emitters_.push_back(e);
    return int(emitters_.size()) - 1;
}

void Lights::finish()
{
    cdf_.clear();
    prob_.clear();
    double total = 0;
    std::vector<double> w;
    for (Emitter& e : emitters_) {
        e.cached_area = e.area();
        const double power =
            double(std::max(e.radiance.luminance(), 0.f)) * e.area() * (e.two_sided ? 2 : 1);
        w.push_back(power);
        total += power;
    }
    double acc = 0;
    for (double x : w) {
        const double p = total > 0 ? x / total : 1.0 / double(w.size());
        prob_.push_back(float(p));
        acc += p;
        cdf_.push_back(float(acc));
    }
    if (!cdf_.empty())
        cdf_.back() = 1.f;
}

namespace {

// Uniform direction in the cone of half-angle θmax around `axis`; 1 − cos θmax is passed
// directly because for small, far spheres cos θmax rounds to 1 in float.
Vec3 sample_cone(Vec3 axis, float one_minus_cos_max, float u1, float u2)
{
    const float one_minus_cos = u1 * one_minus_cos_max;
    const float cos_t = 1 - one_minus_cos;
    const float sin_t = std::sqrt(std::max(0.f, one_minus_cos * (2 - one_minus_cos)));
    const float phi = 2 * kPi * u2;
    const Frame f = Frame::from_normal(axis);
    return f.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t});
}

float sphere_one_minus_cos_max(float d2, float r2)
{
    const float sin2 = r2 / d2;
    return sin2 / (1 + std::sqrt(std::max(0.f, 1 - sin2)));
}

}  // namespace

std::optional<LightSample> Lights::sample(Vec3 p, float u_select, float u1, float u2) const
{
    if (emitters_.empty())
        return std::nullopt;
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u_select);
    const int i = int(std::min<std::ptrdiff_t>(it - cdf_.begin(), std::ptrdiff_t(cdf_.size()) - 1));
    const Emitter& e = emitters_[std::size_t(i)];
    const float p_select = prob_[std::size_t(i)];
    if (p_select <= 0)
        return std::nullopt;

    if (e.kind == Emitter::Kind::Sphere) {
        const Vec3 to_c = e.center - p;
        const float d2 = length_squared(to_c), r2 = e.radius * e.radius;
        if (d2 > r2 * 1.0001f) {
            const float d = std::sqrt(d2);
            const float omc = sphere_one_minus_cos_max(d2, r2);
            const Vec3 wi = sample_cone(to_c / d, omc, u1, u2);
            // Nearest intersection of the ray p + t·wi with the sphere.
            const float b = dot(wi, to_c);
            const float disc = std::max(0.f, r2 - (d2 - b * b));
            const float t = std::max(0.f, b - std::sqrt(disc));
            const Vec3 q = p + wi * t;
            Vec3 n = normalize(q - e.center);
            if (e.inward)
                n = -n;
            const float pdf = p_select / (2 * kPi * omc);
            return LightSample{wi, t, e.emitted(n, -wi), pdf};
        }
        // Inside the sphere: uniform over its area.
        const float z = 1 - 2 * u1, rr = std::sqrt(std::max(0.f, 1 - z * z)), phi = 2 * kPi * u2;
        const Vec3 nrm{rr * std::cos(phi), rr * std::sin(phi), z};
        const Vec3 q = e.center + nrm * e.radius;
        const Vec3 v = q - p;
        const float dist2 = length_squared(v);
        if (dist2 <= 0)
            return std::nullopt;
        const float dist = std::sqrt(dist2);
        const Vec3 wi = v / dist;
        const Vec3 n = e.inward ? -nrm : nrm;
        const float cos_l = std::abs(dot(nrm, wi));
        if (cos_l <= 0)
            return std::nullopt;
        return LightSample{wi, dist, e.emitted(n, -wi), p_select * dist2 / (cos_l * e.cached_area)};
    }

    // Triangle: uniform barycentrics.
    const float su = std::sqrt(u1);
    const float b0 = 1 - su, b1 = u2 * su;
    const Vec3 q = e.p0 * b0 + e.p1 * b1 + e.p2 * (1 - b0 - b1);
    const Vec3 v = q - p;
    const float dist2 = length_squared(v);
    if (dist2 <= 0)
        return std::nullopt;
    const float dist = std::sqrt(dist2);
    const Vec3 wi = v / dist;
    const float cos_l = std::abs(dot(e.normal, wi));
    if (cos_l <= 1e-7f)
        return std::nullopt;
    return LightSample{wi, dist, e.emitted(e.normal, -wi),
                       p_select * dist2 / (cos_l * e.cached_area)};
}

float Lights::pdf(Vec3 p, int i, Vec3 q, Vec3 n) const
{
    if (i < 0 || i >= int(emitters_.size()))
        return 0;
    const Emitter& e = emitters_[std::size_t(i)];
    const float p_select = prob_[std::size_t(i)];
    const Vec3 v = q - p;
    const float dist2 = length_squared(v);
    if (dist2 <= 0)
        return 0;
    if (e.kind == Emitter::Kind::Sphere) {
        const float d2 = length_squared(e.center - p), r2 = e.radius * e.radius;
        if (d2 > r2 * 1.0001f)
            return p_select / (2 * kPi * sphere_one_minus_cos_max(d2, r2));
    }
    const float cos_l = std::abs(dot(n, v)) / std::sqrt(dist2);
    if (cos_l <= 1e-7f || e.cached_area <= 0)
        return 0;
    return p_select * dist2 / (cos_l * e.cached_area);
}

}  // namespace statmc::render
