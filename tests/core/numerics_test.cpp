// numerics.h: gamma(n) against its definition and as a true error bound; next_float_up/down at the awkward
// values (zeros of both signs, denormals, the largest float, infinities, NaN).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "raystep/geometry/numerics.h"

namespace raystep {
namespace {

TEST(Numerics, GammaMatchesDefinition) {
  const double u = std::ldexp(1.0, -24);  // unit roundoff of float
  for (int n = 1; n <= 10; ++n)
    EXPECT_NEAR(gamma(n), n * u / (1 - n * u), 1e-7 * gamma(n)) << n;  // float rounding of the constant
  EXPECT_GT(gamma(3), gamma(2));
  EXPECT_FLOAT_EQ(kMachineEpsilon, FLT_EPSILON / 2);
}

// gamma(n) bounds the relative error of n chained roundings: a product of three floats (two roundings) and a
// sum of four (three roundings).
TEST(Numerics, GammaBoundsRoundingOfChainedOperations) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.001f, 1000.f);
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    float a = u(rng), b = u(rng), c = u(rng), d = u(rng);
    // a*b is exact in double; the second double product adds a relative 2^-53, covered by the 1e-15 margin.
    double exact_product = double(a) * double(b) * double(c);
    float product = a * b * c;
    ASSERT_LE(std::fabs(product - exact_product), (gamma(2) + 1e-15) * exact_product);
    worst = std::fmax(worst, std::fabs(product - exact_product) / exact_product);
    double exact_sum = double(a) + double(b) + double(c) + double(d);  // exact: < 53 significant bits here
    float sum = ((a + b) + c) + d;
    ASSERT_LE(std::fabs(sum - exact_sum), gamma(3) * exact_sum);
  }
  EXPECT_GT(worst, gamma(1));  // the bound is not loose: two roundings do exceed one rounding's bound
}

TEST(Numerics, NextFloatUpAndDownAtOrdinaryValues) {
  EXPECT_EQ(next_float_up(1.f), 1.f + FLT_EPSILON);
  EXPECT_EQ(next_float_down(1.f), 1.f - FLT_EPSILON / 2);
  EXPECT_EQ(next_float_up(-1.f), -1.f + FLT_EPSILON / 2);
  EXPECT_EQ(next_float_down(-1.f), -1.f - FLT_EPSILON);
  EXPECT_EQ(next_float_up(1e6f), std::nextafter(1e6f, kInfinity));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1e6f, 1e6f);
  for (int i = 0; i < 10000; ++i) {
    float x = u(rng) * std::pow(10.f, float(int(rng() % 20) - 10));
    ASSERT_EQ(next_float_up(x), std::nextafter(x, kInfinity)) << x;
    ASSERT_EQ(next_float_down(x), std::nextafter(x, -kInfinity)) << x;
    ASSERT_EQ(next_float_down(next_float_up(x)), x);
  }
}

TEST(Numerics, NextFloatAtZerosDenormalsAndInfinities) {
  const float tiny = std::numeric_limits<float>::denorm_min();
  EXPECT_EQ(next_float_up(0.f), tiny);
  EXPECT_EQ(next_float_up(-0.f), tiny);  // -0 and +0 are the same number
  EXPECT_EQ(next_float_down(0.f), -tiny);
  EXPECT_EQ(next_float_down(-0.f), -tiny);
  EXPECT_EQ(next_float_up(-tiny), 0.f);
  EXPECT_EQ(next_float_down(tiny), 0.f);
  EXPECT_EQ(next_float_up(FLT_MAX), kInfinity);
  EXPECT_EQ(next_float_down(-FLT_MAX), -kInfinity);
  EXPECT_EQ(next_float_up(kInfinity), kInfinity);
  EXPECT_EQ(next_float_down(-kInfinity), -kInfinity);
  EXPECT_EQ(next_float_up(-kInfinity), -FLT_MAX);
  EXPECT_EQ(next_float_down(kInfinity), FLT_MAX);
  EXPECT_TRUE(std::isnan(next_float_up(std::nanf(""))));
  EXPECT_TRUE(std::isnan(next_float_down(std::nanf(""))));
}

TEST(Numerics, BitsRoundTrip) {
  EXPECT_EQ(float_to_bits(1.f), 0x3f800000u);
  EXPECT_EQ(float_to_bits(-0.f), 0x80000000u);
  EXPECT_EQ(bits_to_float(0x7f800000u), kInfinity);
  EXPECT_EQ(float_to_bits(bits_to_float(0x7fc00123u)), 0x7fc00123u);  // NaN payload kept
}

// Directed rounding of a sum or difference: never inside the exact result, and exact results kept exact.
// Checked in double, where the sum of two floats of these magnitudes is exact.
TEST(Numerics, SubRoundDownAndAddRoundUp) {
  EXPECT_EQ(sub_round_down(0.5f, 0.5f), 0.f);  // a sphere of radius 0.5 at y = 0.5 rests on y = 0
  EXPECT_FALSE(std::signbit(sub_round_down(0.5f, 0.5f)));
  EXPECT_EQ(add_round_up(0.25f, 0.5f), 0.75f);
  EXPECT_EQ(sub_round_down(1.f, 1e-8f), std::nextafter(1.f, 0.f));  // 1 - 1e-8 rounds to 1: step down
  EXPECT_EQ(add_round_up(1.f, 1e-8f), std::nextafter(1.f, 2.f));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-100.f, 100.f), r(0.f, 3.f);
  for (int i = 0; i < 100000; ++i) {
    float a = u(rng), b = r(rng);
    double lo = double(a) - double(b), hi = double(a) + double(b);
    float l = sub_round_down(a, b), h = add_round_up(a, b);
    ASSERT_LE(double(l), lo) << a << " - " << b;
    ASSERT_GE(double(h), hi) << a << " + " << b;
    // At most one step: the float just below (above) is already inside.
    ASSERT_GT(double(std::nextafter(l, INFINITY)), lo) << a << " - " << b;
    ASSERT_LT(double(std::nextafter(h, -INFINITY)), hi) << a << " + " << b;
  }
}

}  // namespace
}  // namespace raystep
