// The guide weight's 2^x (core/src/simd_exp2.h), in its scalar build: the polynomial and
// the reduction are the same source in all three kernels, which the filter tests compare
// against each other and against the double-precision reference.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "simd_exp2.h"
#include "simd_scalar.h"

namespace statmc {
namespace {

float exp2_scalar(float x) { return simd::exp2_nonpositive<simd::Scalar>(x); }

TEST(Exp2, WithinThreeUlpOverTheNormalRange)
{
    // Dense in [−125, 0]: every fraction, every power of two the kernels keep.
    double worst = 0;
    for (int i = 0; i <= 1250000; ++i) {
        const float x = -125.f * float(i) / 1250000.f;
        const double exact = std::exp2(double(x));
        worst = std::max(worst, std::abs(exp2_scalar(x) - exact) / exact);
    }
    EXPECT_LT(worst, 3 * std::numeric_limits<float>::epsilon() / 2)
        << "max relative error " << worst;
}

TEST(Exp2, ExactAtIntegersAndOneAtZero)
{
    EXPECT_EQ(exp2_scalar(0.f), 1.f);
    EXPECT_EQ(exp2_scalar(-0.f), 1.f);
    for (int n = -125; n <= 0; ++n)
        EXPECT_EQ(exp2_scalar(float(n)), std::ldexp(1.f, n)) << n;
}

TEST(Exp2, VanishesBelowTheNormalRangeWithoutDenormals)
{
    // Below 2^−125 the weight is 0, never a denormal (slow FMAs) and never NaN, however
    // far the argument goes: guides that differ wildly give squared differences ~1e35.
    for (float x : {-125.6f, -126.f, -149.f, -1000.f, -1e20f, -3e38f})
        EXPECT_EQ(exp2_scalar(x), 0.f) << x;
    EXPECT_GT(exp2_scalar(-125.f), 0.f);
}

}  // namespace
}  // namespace statmc
