#include "statmc/core/critical_values.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>

namespace statmc {

double CriticalValues::exact(double alpha, double df)
{
    // complement() keeps full precision for the small upper tails that α/2 asks for.
    if (std::isinf(df))
        return boost::math::quantile(boost::math::complement(boost::math::normal(), alpha / 2));
    return boost::math::quantile(
        boost::math::complement(boost::math::students_t(df), alpha / 2));
}

CriticalValues::CriticalValues(double alpha) : alpha_(alpha)
{
    if (!(alpha > 0 && alpha < 1))
        throw std::invalid_argument("alpha must be in (0, 1), got " + std::to_string(alpha));
    dense_.resize(kDenseLimit + 1, std::numeric_limits<double>::quiet_NaN());
    for (int df = 1; df <= kDenseLimit; ++df)
        dense_[df] = exact(alpha, df);
    tail_.resize(kTailNodes + 1);
    tail_[0] = exact(alpha, std::numeric_limits<double>::infinity());
    for (int k = 1; k <= kTailNodes; ++k)
        tail_[k] = exact(alpha, double(kTailNodes) * kDenseLimit / k);
}

double CriticalValues::gamma(double df) const
{
    if (!(df >= 1))
        return std::numeric_limits<double>::quiet_NaN();
    if (df <= kDenseLimit && df == std::floor(df))
        return dense_[int(df)];
    if (df <= kDenseLimit)
        return exact(alpha_, df);  // fractional df: rare, not in the hot path
    const double u = double(kTailNodes) * kDenseLimit / df;  // in [0, kTailNodes)
    const int k = int(u);
    const double f = u - k;
    return tail_[k] + f * (tail_[k + 1] - tail_[k]);
}

}  // namespace statmc
