// Critical values of the two-sided t-test against published tables.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "statmc/core/critical_values.h"

namespace statmc {
namespace {

struct TableRow {
    double alpha;  // two-sided
    double df;
    double t;  // published, 3 decimals
};

// Student-t upper-tail critical values as printed in standard statistical tables
// (e.g. NIST/SEMATECH e-Handbook, Table 1.3.6.7.2), at one-sided tail α/2.
constexpr TableRow kTable[] = {
    {0.05, 1, 12.706}, {0.05, 2, 4.303},   {0.05, 5, 2.571},   {0.05, 10, 2.228},
    {0.05, 30, 2.042}, {0.05, 100, 1.984}, {0.01, 1, 63.657},  {0.01, 5, 4.032},
    {0.01, 10, 3.169}, {0.01, 30, 2.750},  {0.01, 100, 2.626}, {0.002, 1, 318.313},
    {0.002, 5, 5.893}, {0.002, 10, 4.144}, {0.002, 30, 3.385}, {0.002, 100, 3.174},
};

TEST(CriticalValues, MatchPublishedTables)
{
    for (const TableRow& row : kTable) {
        const CriticalValues cv(row.alpha);
        // Tables print 3 decimals (and at df 1 some round the 6th digit differently).
        EXPECT_NEAR(cv.gamma(row.df), row.t, std::max(0.0015, 2e-5 * row.t))
            << "alpha " << row.alpha << " df " << row.df;
    }
}

TEST(CriticalValues, DefaultAlphaMatchesMethodDescription)
{
    // docs/method.md §3: γ_w ≈ 2.81 for large n, 4.32 at df 6 (α = 0.005).
    const CriticalValues cv(0.005);
    EXPECT_NEAR(cv.gamma(6), 4.317, 0.001);
    EXPECT_NEAR(cv.gamma(1e7), 2.807, 0.001);
    // The normal quantile z_{0.9975} = 2.8070338...
    EXPECT_NEAR(cv.gamma(std::numeric_limits<double>::infinity()), 2.8070338, 1e-6);
}

TEST(CriticalValues, TailInterpolationIsExactToNineDigits)
{
    for (double alpha : {0.002, 0.005, 0.05}) {
        const CriticalValues cv(alpha);
        for (double df : {1024.0, 1025.0, 1500.5, 2046.0, 4094.0, 65534.0, 1e6, 3.3e8})
            EXPECT_NEAR(cv.gamma(df), CriticalValues::exact(alpha, df), 1e-8) << df;
        // A table sized for small df still answers large df exactly (slow path).
        EXPECT_NEAR(CriticalValues(alpha, 126).gamma(5000.0), CriticalValues::exact(alpha, 5000.0),
                    1e-12);
    }
}

TEST(CriticalValues, DecreaseWithDegreesOfFreedom)
{
    const CriticalValues cv(0.005);
    double previous = cv.gamma(1);
    for (double df = 2; df < 1e6; df = std::ceil(df * 1.1)) {
        const double g = cv.gamma(df);
        EXPECT_LT(g, previous) << df;
        previous = g;
    }
}

TEST(CriticalValues, RejectsInvalidArguments)
{
    EXPECT_THROW(CriticalValues(0.0), std::invalid_argument);
    EXPECT_THROW(CriticalValues(1.0), std::invalid_argument);
    EXPECT_THROW(CriticalValues(std::nan("")), std::invalid_argument);
    EXPECT_TRUE(std::isnan(CriticalValues(0.005).gamma(0)));
}

}  // namespace
}  // namespace statmc
