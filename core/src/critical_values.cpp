#include "statmc/core/critical_values.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
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
    return boost::math::quantile(boost::math::complement(boost::math::students_t(df), alpha / 2));
}

CriticalValues::CriticalValues(double alpha, double max_df) : alpha_(alpha), max_df_(max_df)
{
    if (!(alpha > 0 && alpha < 1))
        throw std::invalid_argument("alpha must be in (0, 1), got " + std::to_string(alpha));
    const int dense_limit = int(std::clamp(std::ceil(max_df), 0.0, double(kDenseLimit)));
    dense_.resize(dense_limit + 1, std::numeric_limits<double>::quiet_NaN());
    for (int df = 1; df <= dense_limit; ++df)
        dense_[df] = exact(alpha, df);
    if (max_df > kDenseLimit) {
        tail_.resize(kTailNodes + 1);
        tail_[0] = exact(alpha, std::numeric_limits<double>::infinity());
        for (int k = 1; k <= kTailNodes; ++k)
            tail_[k] = exact(alpha, double(kTailNodes) * kDenseLimit / k);
    }
}

std::shared_ptr<const CriticalValues> CriticalValues::shared(double alpha, double max_df)
{
    static std::mutex mutex;
    static std::map<double, std::shared_ptr<const CriticalValues>> tables;
    const std::lock_guard<std::mutex> lock(mutex);
    auto& table = tables[alpha];
    if (!table || table->max_df() < max_df) {
        // Grow geometrically so that slowly rising sample counts rebuild rarely.
        const double previous = table ? table->max_df() : 0.0;
        table = std::make_shared<const CriticalValues>(alpha, std::max(max_df, 2 * previous));
    }
    return table;
}

double CriticalValues::gamma(double df) const
{
    if (!(df >= 1))
        return std::numeric_limits<double>::quiet_NaN();
    if (df < double(dense_.size()) && df == std::floor(df))
        return dense_[int(df)];
    if (df <= kDenseLimit || tail_.empty())
        return exact(alpha_, df);  // fractional or beyond the table: rare, slow, exact
    const double u = double(kTailNodes) * kDenseLimit / df;  // in [0, kTailNodes)
    const int k = int(u);
    const double f = u - k;
    return tail_[k] + f * (tail_[k + 1] - tail_[k]);
}

double normal_critical_value(double alpha)
{
    if (!(alpha > 0 && alpha < 1))
        throw std::invalid_argument("normal_critical_value: alpha must be in (0, 1)");
    return boost::math::quantile(boost::math::complement(boost::math::normal(), alpha / 2));
}

}  // namespace statmc
