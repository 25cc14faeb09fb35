// Critical values of the two-sided Student-t test, tabulated so that the filter never
// calls Boost per pixel.
#pragma once

#include <memory>
#include <vector>

namespace statmc {

/// γ_w(df) = t-quantile at 1 − α/2. Exact (Boost.Math) for df ≤ kDenseLimit; above it,
/// interpolated linearly in 1/df between exact nodes down to the normal quantile at
/// df = ∞, which is accurate to ~1e-9 because γ_w is smooth in 1/df.
class CriticalValues {
public:
    static constexpr int kDenseLimit = 1024;
    static constexpr int kTailNodes = 64;

    /// α in (0, 1); throws std::invalid_argument otherwise. Values up to `max_df` are
    /// tabulated (each costs a Boost quantile); larger df fall back to exact evaluation.
    explicit CriticalValues(double alpha, double max_df = 1e300);

    /// A process-wide table for α covering df ≤ max_df, built once and then shared:
    /// progressive renders and batch jobs filter many images at one α.
    static std::shared_ptr<const CriticalValues> shared(double alpha, double max_df);

    double alpha() const { return alpha_; }
    double max_df() const { return max_df_; }
    /// df ≥ 1 (df < 1 is a caller error and returns NaN); non-integer df is allowed.
    double gamma(double df) const;

    /// The exact value from Boost.Math, for tests and table building.
    static double exact(double alpha, double df);

private:
    double alpha_;
    double max_df_;
    std::vector<double> dense_;  // index df, 1..kDenseLimit
    std::vector<double> tail_;   // node k at 1/df = k / (kTailNodes * kDenseLimit)
};

/// z for a two-sided confidence of 1 − α (α in (0, 1)): the normal quantile at 1 − α/2.
double normal_critical_value(double alpha);

}  // namespace statmc
