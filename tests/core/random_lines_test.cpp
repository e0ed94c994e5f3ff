// Crofton's lines (random_lines.h): the share of random lines through a box's bounding sphere that meet the
// box is its mean shadow over the sphere's, (S/4) / (pi R^2), for boxes of every shape and at every scale.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "raystep/accel/random_lines.h"

namespace raystep {
namespace {

TEST(RandomLines, CubeIsMetByTwoOverPiOfTheLines) {
  // A cube of side a: S = 6 a^2, R = a sqrt(3) / 2, so (S/4) / (pi R^2) = 2 / pi.
  const Bounds3 cube{glm::vec3(0), glm::vec3(1)};
  LinesMeetingBox m = lines_meeting_box(cube, 200000, 7);
  EXPECT_NEAR(m.predicted, 2.0 / M_PI, 1e-6);
  // 200,000 lines: the standard deviation of the share is sqrt(p (1 - p) / n) = 0.0011.
  EXPECT_NEAR(m.measured, m.predicted, 0.005);
}

TEST(RandomLines, FlatAndFarBoxesAgreeWithCauchyCrofton) {
  for (const Bounds3& box : {Bounds3{glm::vec3(-6, 0, -6), glm::vec3(6, 0.5f, 6)},      // a slab
                             Bounds3{glm::vec3(0), glm::vec3(1e-4f, 2e-4f, 3e-4f)},   // tiny
                             Bounds3{glm::vec3(1e6f), glm::vec3(1e6f + 10, 1e6f + 1, 1e6f + 3)}}) {
    LinesMeetingBox m = lines_meeting_box(box, 100000, 11);
    const float r = 0.5f * glm::length(box.extent());
    EXPECT_NEAR(m.predicted, box.surface_area() / 4.0 / (M_PI * r * r), 1e-6 * m.predicted);
    EXPECT_NEAR(m.measured, m.predicted, 0.01) << box.lo.x;
  }
}

TEST(RandomLines, EveryLineCrossesItsSphere) {
  Pcg32 rng(5, 0);
  const glm::vec3 centre(3, -2, 1);
  for (int i = 0; i < 1000; ++i) {
    const Ray ray = random_line(rng, centre, 2.f);
    // The closest point of the line to the centre lies within the radius, 2 radii along the direction.
    const glm::vec3 to = centre - ray.origin;
    const float along = glm::dot(to, ray.direction);
    EXPECT_NEAR(along, 4.f, 1e-3f);
    EXPECT_LE(glm::length(to - along * ray.direction), 2.f + 1e-4f);
    EXPECT_NEAR(glm::length(ray.direction), 1.f, 1e-5f);
  }
}

TEST(RandomLines, EmptyBoxPredictsNothing) {
  LinesMeetingBox m = lines_meeting_box(Bounds3{}, 100, 1);
  EXPECT_EQ(m.measured, 0.0);
  EXPECT_EQ(m.predicted, 0.0);
}

}  // namespace
}  // namespace raystep
