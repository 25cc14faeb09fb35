#include "statmc/core/variance_interval.h"

#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/normal.hpp>

namespace statmc {

double LogVarianceInterval::lower_variance() const { return std::exp(centre - half_width); }

double LogVarianceInterval::upper_variance() const { return std::exp(centre + half_width); }

bool LogVarianceInterval::contains_variance(double variance) const
{
    return variance > 0 && std::abs(std::log(variance) - centre) <= half_width;
}

bool has_bonett_interval(double n, double m2, double m4, double z)
{
    return n >= 4 && n > z && m2 > 0 && m4 >= 0;
}

std::optional<LogVarianceInterval> bonett_interval(double n, double m2, double m4, double z)
{
    if (!has_bonett_interval(n, m2, m4, z))
        return std::nullopt;
    const double c = n / (n - z);
    const double kurtosis = n * m4 / (m2 * m2);
    // γ ≥ 1 for any sample (Cauchy-Schwarz) and (n − 3)/n < 1, so the root is real; the
    // clamp only absorbs rounding.
    const double spread = std::max(kurtosis - (n - 3) / n, 0.0);
    const double se = c * std::sqrt(spread / (n - 1));
    return LogVarianceInterval{std::log(c * m2 / (n - 1)), z * se};
}

double normal_critical_value(double alpha)
{
    if (!(alpha > 0 && alpha < 1))
        throw std::invalid_argument("normal_critical_value: alpha must be in (0, 1)");
    return boost::math::quantile(boost::math::complement(boost::math::normal(), alpha / 2));
}

}  // namespace statmc
