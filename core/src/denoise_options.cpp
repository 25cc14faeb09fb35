#include "statmc/core/denoise_options.h"

#include <charconv>
#include <cmath>

namespace statmc {

namespace {

bool positive(float v) { return std::isfinite(v) && v > 0; }

// Shortest text that reads back to the same value: users see "1e-09", not "0.000000".
std::string number(double v)
{
    char buf[32];
    const auto result = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, result.ptr);
}

}  // namespace

DenoiseOptions DenoiseOptions::paper()
{
    DenoiseOptions o;
    o.firefly_ratio = 0;
    o.guide_noise = false;
    return o;
}

std::string DenoiseOptions::validate() const
{
    if (radius < 0 || radius > 1000)
        return "radius must be in [0, 1000], got " + std::to_string(radius);
    if (!(alpha > 0 && alpha < 1))
        return "alpha must be in (0, 1), got " + number(alpha);
    if (!positive(sigma_spatial))
        return "sigma_s must be > 0, got " + number(sigma_spatial);
    if (!positive(sigma_albedo))
        return "sigma_albedo must be > 0, got " + number(sigma_albedo);
    if (!positive(sigma_normal))
        return "sigma_normal must be > 0, got " + number(sigma_normal);
    if (!(std::isfinite(firefly_ratio) && (firefly_ratio == 0 || firefly_ratio >= 1)))
        return "fireflies must be 0 (off) or a variance ratio >= 1, got " + number(firefly_ratio);
    return {};
}

}  // namespace statmc
