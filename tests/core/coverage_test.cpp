// Exact area coverage against areas worked out by hand.
#include <gtest/gtest.h>

#include <random>

#include "raystep/render/coverage.h"

namespace raystep {
namespace {

using Polygon = std::vector<glm::dvec2>;

TEST(Coverage, ShoelaceAreaAndOrientation) {
  Polygon square = {{0, 0}, {2, 0}, {2, 3}, {0, 3}};
  EXPECT_DOUBLE_EQ(signed_area(square), 6.0);
  Polygon reversed(square.rbegin(), square.rend());
  EXPECT_DOUBLE_EQ(signed_area(reversed), -6.0);
  EXPECT_DOUBLE_EQ(signed_area({}), 0.0);
}

TEST(Coverage, FullEmptyAndHalfPixels) {
  Polygon big = {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  EXPECT_DOUBLE_EQ(pixel_coverage(big, 0, 0), 1.0);
  EXPECT_DOUBLE_EQ(pixel_coverage(big, -5, 4), 1.0);
  EXPECT_DOUBLE_EQ(pixel_coverage(big, 5, 0), 0.0);  // touches only the boundary
  EXPECT_DOUBLE_EQ(pixel_coverage(big, 20, 20), 0.0);
  // The pixel's lower-left half: the triangle below its diagonal.
  Polygon half = {{3, 7}, {4, 7}, {3, 8}};
  EXPECT_DOUBLE_EQ(pixel_coverage(half, 3, 7), 0.5);
  // A vertical edge at x = 10.3 crossing pixel (10, 2): 0.7 of it covered, either orientation.
  Polygon right = {{10.3, -100}, {100, -100}, {100, 100}, {10.3, 100}};
  EXPECT_NEAR(pixel_coverage(right, 10, 2), 0.7, 1e-12);
  Polygon right_cw(right.rbegin(), right.rend());
  EXPECT_NEAR(pixel_coverage(right_cw, 10, 2), 0.7, 1e-12);
}

TEST(Coverage, SlantedEdgeTrapezoid) {
  // Half-plane y <= 0.25 + 0.5 x over pixel (0, 0): the area below the line is the trapezoid
  // with heights 0.25 and 0.75, area 0.5.
  Polygon below = {{-10, -10}, {10, -10}, {10, 0.25 + 5}, {-10, 0.25 - 5}};
  EXPECT_NEAR(pixel_coverage(below, 0, 0), 0.5, 1e-12);
  // The same line over pixel (1, 0) runs from height 0.75 to 1.25: it leaves the pixel at x = 1.5, and the
  // uncovered part is the triangle above it with legs 0.5 and 0.25.
  EXPECT_NEAR(pixel_coverage(below, 1, 0), 1.0 - 0.5 * 0.5 * 0.25, 1e-12);
}

TEST(Coverage, PixelCoveragesSumToThePolygonArea) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 20.0);
  for (int trial = 0; trial < 20; ++trial) {
    Polygon tri = {{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
    double sum = 0.0;
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x) {
        double c = pixel_coverage(tri, x, y);
        EXPECT_GE(c, 0.0);
        EXPECT_LE(c, 1.0 + 1e-12);
        sum += c;
      }
    EXPECT_NEAR(sum, std::fabs(signed_area(tri)), 1e-9);
  }
}

TEST(Coverage, SimpleNonConvexPolygon) {
  // An L shape: the 3 x 3 square minus its top-right 2 x 2 corner; area 5, clipped into pixels.
  Polygon l_shape = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  double sum = 0.0;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) sum += pixel_coverage(l_shape, x, y);
  EXPECT_NEAR(sum, 5.0, 1e-12);
  EXPECT_DOUBLE_EQ(pixel_coverage(l_shape, 2, 2), 0.0);
  // A notch inside one pixel: the pixel [0,1]^2 minus a triangular notch of area 0.25 * 0.5 / 2.
  Polygon notch = {{0, 0}, {1, 0}, {1, 1}, {0.75, 1}, {0.5, 0.5}, {0.25, 1}, {0, 1}};
  EXPECT_NEAR(pixel_coverage(notch, 0, 0), 1.0 - 0.125, 1e-12);
}

}  // namespace
}  // namespace raystep
