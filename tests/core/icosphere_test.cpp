// icosphere.h: the subdivided icosahedron is a closed, consistently wound mesh on the sphere: V, E, F as
// predicted, Euler characteristic 2, every edge shared by exactly two triangles (once in each direction),
// no duplicate vertices, outward winding, and a volume that converges to the ball's.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include "raystep/geometry/icosphere.h"
#include "raystep/scene/geometry.h"

namespace raystep {
namespace {

TEST(Icosphere, CountsAndEulerCharacteristic) {
  for (int n = 0; n <= 4; ++n) {
    Icosphere m = make_icosphere(n);
    size_t p = size_t(1) << (2 * n);  // 4^n
    EXPECT_EQ(m.positions.size(), 10 * p + 2) << n;
    EXPECT_EQ(m.triangles.size(), 20 * p) << n;
    std::set<std::pair<uint32_t, uint32_t>> edges;
    for (const glm::uvec3& t : m.triangles)
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    EXPECT_EQ(edges.size(), 30 * p) << n;
    EXPECT_EQ(long(m.positions.size()) - long(edges.size()) + long(m.triangles.size()), 2) << n;
  }
}

// Closed and consistently oriented: each directed edge occurs once, and its reverse once.
TEST(Icosphere, EveryEdgeSharedByExactlyTwoTriangles) {
  for (int n = 0; n <= 3; ++n) {
    Icosphere m = make_icosphere(n, glm::vec3(3.f, -2.f, 1.f), 2.5f);
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const glm::uvec3& t : m.triangles) {
      ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
      for (int k = 0; k < 3; ++k) {
        ASSERT_LT(t[k], m.positions.size());
        ++directed[{t[k], t[(k + 1) % 3]}];
      }
    }
    for (const auto& [edge, count] : directed) {
      ASSERT_EQ(count, 1) << n;
      auto reverse = directed.find({edge.second, edge.first});
      ASSERT_TRUE(reverse != directed.end()) << n;
      ASSERT_EQ(reverse->second, 1) << n;
    }
  }
}

TEST(Icosphere, VerticesOnTheSphereDistinctAndWoundOutwards) {
  const glm::vec3 c(1e3f, 2e3f, -5e2f);
  const float r = 7.f;
  Icosphere m = make_icosphere(3, c, r);
  std::set<std::tuple<float, float, float>> seen;
  for (const glm::vec3& p : m.positions) {
    // Rounded once to float: off the sphere by at most about ulp(|c| + r).
    EXPECT_NEAR(glm::length(glm::dvec3(p) - glm::dvec3(c)), r, 2e-7 * (glm::length(c) + r));
    EXPECT_TRUE(seen.insert({p.x, p.y, p.z}).second) << "duplicate vertex";
  }
  for (size_t i = 0; i < m.triangles.size(); ++i) {
    glm::dvec3 p0(m.vertex(i, 0)), p1(m.vertex(i, 1)), p2(m.vertex(i, 2));
    glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    EXPECT_GT(glm::dot(n, (p0 + p1 + p2) / 3.0 - glm::dvec3(c)), 0.0) << i;
  }
}

// Signed volume by the divergence theorem: sum of p0 . (p1 x p2) / 6. It grows towards 4/3 pi r^3 from
// below (an inscribed polyhedron); the regular icosahedron's is known in closed form.
TEST(Icosphere, VolumeConvergesToTheBall) {
  auto volume = [](const Icosphere& m) {
    double v = 0;
    for (size_t i = 0; i < m.triangles.size(); ++i)
      v += glm::dot(glm::dvec3(m.vertex(i, 0)),
                    glm::cross(glm::dvec3(m.vertex(i, 1)), glm::dvec3(m.vertex(i, 2))));
    return v / 6;
  };
  const double pi = 3.14159265358979323846, ball = 4.0 / 3.0 * pi;
  // Icosahedron with circumradius 1: edge a = 1 / sin(2 pi / 5), volume 5/12 (3 + sqrt 5) a^3.
  double a = 1 / std::sin(2 * pi / 5);
  EXPECT_NEAR(volume(make_icosphere(0)), 5.0 / 12.0 * (3 + std::sqrt(5.0)) * a * a * a, 1e-5);
  double previous = 0;
  for (int n = 0; n <= 4; ++n) {
    double v = volume(make_icosphere(n));
    EXPECT_GT(v, previous);
    EXPECT_LT(v, ball);
    previous = v;
  }
  EXPECT_NEAR(previous, ball, 0.01 * ball);  // level 4: within 1 %
}

TEST(Icosphere, AddToGeometryKeepsSharedVerticesBitIdentical) {
  Icosphere m = make_icosphere(2, glm::vec3(0.5f), 2.f);
  Geometry g;
  g.add_sphere(Sphere{});  // something before it: ids start after
  uint32_t object = add_to_geometry(m, g, "ball", 3);
  ASSERT_EQ(g.size(), 1 + m.triangles.size());
  EXPECT_EQ(g.objects()[object].name, "ball");
  EXPECT_EQ(g.objects()[object].first_prim, 1u);
  EXPECT_EQ(g.objects()[object].prim_count, m.triangles.size());
  EXPECT_EQ(g.material(1), 3u);
  for (size_t i = 0; i < m.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(g.vertex(uint32_t(1 + i), k), m.vertex(i, k));
  EXPECT_NEAR(g.objects()[object].bounds.hi.x, 2.5f, 1e-6);
  EXPECT_NEAR(g.objects()[object].bounds.lo.y, -1.5f, 1e-6);
}

TEST(Icosphere, RejectsBadSubdivisionLevels) {
  EXPECT_THROW(make_icosphere(-1), std::invalid_argument);
  EXPECT_THROW(make_icosphere(9), std::invalid_argument);
}

}  // namespace
}  // namespace raystep
