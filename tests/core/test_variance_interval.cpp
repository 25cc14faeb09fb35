// Bonett's variance interval from online sums: coverage measured by simulation against
// binomial bounds, and the fourth central moment it reads, kept and merged exactly.
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "statmc/core/moments.h"
#include "statmc/core/variance_interval.h"

namespace statmc {
namespace {

constexpr int kTrials = 4000;

struct Distribution {
    const char* name;
    double variance;  // the true σ²
    std::function<double(std::mt19937_64&)> draw;
};

const std::vector<Distribution>& distributions()
{
    static const std::vector<Distribution> all = {
        {"normal", 4.0,
         [](std::mt19937_64& r) { return std::normal_distribution<double>(3, 2)(r); }},
        {"uniform", 1.0 / 12,
         [](std::mt19937_64& r) { return std::uniform_real_distribution<double>()(r); }},
        {"exponential", 4.0,
         [](std::mt19937_64& r) { return std::exponential_distribution<double>(0.5)(r); }},
        {"lognormal", (std::exp(0.25) - 1) * std::exp(0.25),
         [](std::mt19937_64& r) { return std::lognormal_distribution<double>(0, 0.5)(r); }},
    };
    return all;
}

const Distribution& named(const std::string& name)
{
    for (const Distribution& d : distributions())
        if (name == d.name)
            return d;
    throw std::invalid_argument(name);
}

// The share of kTrials samples of n values whose interval holds the true variance.
double coverage(const Distribution& d, int n, double alpha, std::uint64_t seed)
{
    std::mt19937_64 rng(seed);
    const double z = normal_critical_value(alpha);
    int covered = 0;
    for (int t = 0; t < kTrials; ++t) {
        CentralMoments<double> m;
        for (int i = 0; i < n; ++i)
            m.add(i, d.draw(rng));
        const auto interval = bonett_interval(n, m.m2, m.m4, z);
        covered += interval && interval->contains_variance(d.variance);
    }
    return double(covered) / kTrials;
}

// 4.5 binomial standard deviations of a share over kTrials at probability p: a correct
// interval falls outside with probability ≈ 7e-6 per check.
double binomial_slack(double p) { return 4.5 * std::sqrt(p * (1 - p) / kTrials); }

TEST(VarianceInterval, NominalCoverageForLightTailedSamples)
{
    // Where the kurtosis estimate is good (normal, uniform), Bonett's interval keeps its
    // nominal rate from 8 values on.
    std::uint64_t seed = 1;
    for (const char* name : {"normal", "uniform"})
        for (double alpha : {0.05, 0.005})
            for (int n : {8, 16, 64, 256}) {
                const double p = 1 - alpha;
                const double c = coverage(named(name), n, alpha, seed++);
                EXPECT_NEAR(c, p, binomial_slack(p) + 0.01)
                    << name << " n=" << n << " alpha=" << alpha;
            }
}

TEST(VarianceInterval, SkewedSamplesApproachNominalCoverageAsValuesAccumulate)
{
    // Skewed samples under-cover at small n (the plain mean in the kurtosis, where Bonett
    // uses a trimmed one: docs/method.md §10 gives the measured table), but the interval
    // is consistent: its coverage rises towards the nominal rate with n.
    std::uint64_t seed = 100;
    for (const char* name : {"exponential", "lognormal"}) {
        const double few = coverage(named(name), 16, 0.05, seed++);
        const double many = coverage(named(name), 1024, 0.05, seed++);
        EXPECT_GT(many - few, binomial_slack(0.9) * std::sqrt(2.0)) << name;
        EXPECT_LT(many, 0.95 + binomial_slack(0.95)) << name << ": over-covers";
        EXPECT_GT(many, 0.90) << name << " at n=1024";
    }
}

TEST(VarianceInterval, NoIntervalWithoutEnoughValuesOrSpread)
{
    const double z = normal_critical_value(0.05);
    EXPECT_FALSE(bonett_interval(3, 1.0, 1.0, z));
    EXPECT_FALSE(bonett_interval(10, 0.0, 0.0, z));
    EXPECT_FALSE(bonett_interval(2.5, 1.0, 1.0, 0.5));
    ASSERT_TRUE(bonett_interval(4, 1.0, 0.3, z));
    EXPECT_THROW(normal_critical_value(0), std::invalid_argument);
    EXPECT_NEAR(normal_critical_value(0.05), 1.959963984540054, 1e-12);
}

TEST(VarianceInterval, MatchesBonettsFormulaOnAWorkedSample)
{
    // x = 1..5: mean 3, m2 = 10, m4 = 34, s² = 2.5, γ = 5·34/100 = 1.7.
    const double z = 1.959963984540054, n = 5;
    const double c = n / (n - z);
    const double se = c * std::sqrt((1.7 - 2.0 / 5) / 4);
    const auto interval = bonett_interval(n, 10, 34, z);
    ASSERT_TRUE(interval);
    EXPECT_NEAR(interval->centre, std::log(c * 2.5), 1e-12);
    EXPECT_NEAR(interval->half_width, z * se, 1e-12);
    EXPECT_NEAR(interval->lower_variance(), std::exp(std::log(c * 2.5) - z * se), 1e-12);
}

}  // namespace
}  // namespace statmc
