// prism.h: the thin closed prism is closed (every edge shared by exactly two triangles, in opposite
// directions), has the promised counts and shape, and its inside rays start inside.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <utility>

#include <glm/geometric.hpp>

#include "raystep/geometry/prism.h"
#include "raystep/scene/geometry.h"

namespace raystep {
namespace {

TEST(Prism, ClosedWithTheRightCountsAndShape) {
  for (int sides : {3, 6, 8}) {
    Prism p = make_prism(sides, 20.0, 0.01, glm::dvec3(5.0, -2.0, 1.0), glm::dvec3(1.0, 0.7, 0.3));
    EXPECT_EQ(p.positions.size(), size_t(2 * sides));
    EXPECT_EQ(p.triangles.size(), size_t(4 * sides - 4));
    // Each directed edge once, and its reverse once: a closed, consistently wound surface.
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const glm::uvec3& t : p.triangles)
      for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
    }
    // Outward winding: each triangle's normal points away from the axis or along it at the ends.
    for (size_t i = 0; i < p.triangles.size(); ++i) {
      glm::dvec3 a(p.vertex(i, 0)), b(p.vertex(i, 1)), c(p.vertex(i, 2));
      glm::dvec3 n = glm::cross(b - a, c - a), centroid = (a + b + c) / 3.0;
      EXPECT_GT(glm::dot(n, centroid - p.center), 0.0) << "triangle " << i;
    }
    // Every vertex on the circle of the given radius, at distance length / 2 along the axis.
    for (const glm::vec3& q : p.positions) {
      glm::dvec3 r = glm::dvec3(q) - p.center;
      double along = glm::dot(r, p.axis);
      EXPECT_NEAR(std::fabs(along), 10.0, 1e-5);
      EXPECT_NEAR(glm::length(r - along * p.axis), 0.01, 1e-6);
    }
  }
  EXPECT_THROW(make_prism(2, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(make_prism(6, 1.0, 0.0), std::invalid_argument);
}

TEST(Prism, InsideRaysStartNearTheAxis) {
  Prism p = make_prism(6, 20.0, 0.01);
  Geometry g;
  EXPECT_EQ(add_to_geometry(p, g), 0u);
  EXPECT_EQ(g.size(), p.triangles.size());
  std::vector<Ray> rays = rays_inside(p, 1000, 3);
  ASSERT_EQ(rays.size(), 1000u);
  for (const Ray& r : rays) {
    glm::dvec3 o = glm::dvec3(r.origin) - p.center;
    double along = glm::dot(o, p.axis);
    EXPECT_LE(std::fabs(along), 9.0 + 1e-6);
    EXPECT_LE(glm::length(o - along * p.axis), 0.25 * 0.01 * std::sqrt(2.0) + 1e-9);
    EXPECT_NEAR(glm::length(r.direction), 1.f, 1e-6f);
  }
}

}  // namespace
}  // namespace raystep
