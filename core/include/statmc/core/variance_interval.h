// A confidence interval for a pixel's variance that does not assume normal samples
// (Bonett 2006), from the central sums M2 and M4 that CentralMoments keeps. It is the
// yardstick of variance denoising (docs/method.md §10): two pixels' variances are alike
// when their intervals on ln σ² overlap.
#pragma once

#include <optional>

namespace statmc {

/// ln σ² ∈ [centre − half_width, centre + half_width] at the interval's confidence.
struct LogVarianceInterval {
    double centre = 0;
    double half_width = 0;

    double lower_variance() const;
    double upper_variance() const;
    bool contains_variance(double variance) const;
};

/// Bonett's interval for the variance of n values with central sums m2 = Σ(x − x̄)² and
/// m4 = Σ(x − x̄)⁴, at two-sided confidence 1 − α given by z = the normal quantile at
/// 1 − α/2:
///
///     c  = n / (n − z)                      (small-sample scale)
///     γ  = n · m4 / m2²                      (kurtosis, from the plain mean)
///     se = c · sqrt((γ − (n − 3)/n) / (n − 1))
///     ln σ² ∈ ln(c · s²) ± z · se,           s² = m2 / (n − 1)
///
/// Bonett centres γ with a trimmed mean; online sums only know the plain mean, which is
/// what is used here (its effect on coverage is measured in tests/core/test_variance_interval.cpp).
/// No interval (nullopt) below 4 values, for n ≤ z, or without spread (m2 ≤ 0).
std::optional<LogVarianceInterval> bonett_interval(double n, double m2, double m4, double z);

/// Whether bonett_interval(n, m2, m4, z) gives an interval, without computing it.
bool has_bonett_interval(double n, double m2, double m4, double z);

/// z for a two-sided confidence of 1 − α (α in (0, 1)).
double normal_critical_value(double alpha);

}  // namespace statmc
