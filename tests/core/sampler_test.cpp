// The per-pixel random streams: reproducible, distinct per pixel and per seed, uniform on [0, 1).
#include <gtest/gtest.h>

#include <cmath>

#include "raystep/util/random.h"

namespace raystep {
namespace {

TEST(Sampler, SameSeedAndPixelGiveTheSameStream) {
  Pcg32 a(42, 1234), b(42, 1234);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u32(), b.next_u32());
}

TEST(Sampler, NeighbouringPixelsAndSeedsDiffer) {
  Pcg32 a(0, 0), b(0, 1), c(1, 0);
  int same_ab = 0, same_ac = 0;
  for (int i = 0; i < 100; ++i) {
    uint32_t x = a.next_u32(), y = b.next_u32(), z = c.next_u32();
    same_ab += x == y;
    same_ac += x == z;
  }
  EXPECT_LT(same_ab, 2);
  EXPECT_LT(same_ac, 2);
}

TEST(Sampler, UniformMomentsAndNoCorrelationBetweenPixels) {
  // Mean 1/2 and variance 1/12; the first numbers of adjacent pixels' streams uncorrelated.
  const int n = 100000;
  double sum = 0, sum2 = 0, cross = 0;
  for (int i = 0; i < n; ++i) {
    Pcg32 p(7, uint64_t(i)), q(7, uint64_t(i) + 1);
    double u = p.uniform(), v = q.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
    cross += (u - 0.5) * (v - 0.5);
  }
  double mean = sum / n, var = sum2 / n - mean * mean;
  // Five standard errors: sigma/sqrt(n) = 0.289/316.
  EXPECT_NEAR(mean, 0.5, 0.0046);
  EXPECT_NEAR(var, 1.0 / 12.0, 0.002);
  EXPECT_NEAR(cross / n / var, 0.0, 0.016);
}

}  // namespace
}  // namespace raystep
