// ray_sets.h: random rays and the watertightness stress set. Determinism by seed; origins inside the 1.5x
// enlarged bounds; uniform unit directions; edge targets exactly at mesh vertices or on edge lines; and the
// stress set against a closed icosphere: every ray that does not merely graze the mesh hits it.
#include <gtest/gtest.h>

#include <cmath>

#include "raystep/geometry/icosphere.h"
#include "raystep/geometry/triangle.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

bool same_bits(const Ray& a, const Ray& b) {
  for (int k = 0; k < 3; ++k)
    if (float_to_bits(a.origin[k]) != float_to_bits(b.origin[k]) ||
        float_to_bits(a.direction[k]) != float_to_bits(b.direction[k]))
      return false;
  return a.tmin == b.tmin && a.tmax == b.tmax;
}

const Bounds3 kBox(glm::vec3(-1.f, 2.f, 10.f), glm::vec3(3.f, 4.f, 10.5f));

TEST(RaySets, OriginBoundsAreEnlargedAboutTheCentre) {
  Bounds3 o = ray_origin_bounds(kBox);
  EXPECT_NEAR(o.lo.x, -2.f, 1e-6);
  EXPECT_NEAR(o.hi.x, 4.f, 1e-6);
  EXPECT_NEAR(o.lo.y, 1.5f, 1e-6);
  EXPECT_NEAR(o.hi.y, 4.5f, 1e-6);
  EXPECT_NEAR(o.lo.z, 9.875f, 1e-6);
  EXPECT_NEAR(o.hi.z, 10.625f, 1e-6);
}

TEST(RaySets, RandomRaysAreDeterministicBySeed) {
  std::vector<Ray> a = random_rays(kBox, 1000, 5), b = random_rays(kBox, 1000, 5),
                   c = random_rays(kBox, 1000, 6);
  ASSERT_EQ(a.size(), 1000u);
  int same_as_other_seed = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(same_bits(a[i], b[i])) << i;
    same_as_other_seed += same_bits(a[i], c[i]);
  }
  EXPECT_EQ(same_as_other_seed, 0);
  // A prefix does not depend on the count.
  std::vector<Ray> shorter = random_rays(kBox, 10, 5);
  for (size_t i = 0; i < shorter.size(); ++i) EXPECT_TRUE(same_bits(shorter[i], a[i]));
}

TEST(RaySets, RandomRaysFillTheEnlargedBoxWithUniformDirections) {
  const size_t n = 40000;
  std::vector<Ray> rays = random_rays(kBox, n, 1);
  Bounds3 allowed = ray_origin_bounds(kBox), seen;
  glm::dvec3 mean(0.0), mean_sq(0.0);
  for (const Ray& r : rays) {
    ASSERT_TRUE(allowed.contains(r.origin));
    seen.extend(r.origin);
    ASSERT_NEAR(glm::length(r.direction), 1.f, 1e-6);
    ASSERT_EQ(r.tmin, 0.f);
    ASSERT_EQ(r.tmax, kInfinity);
    mean += glm::dvec3(r.direction);
    mean_sq += glm::dvec3(r.direction) * glm::dvec3(r.direction);
  }
  mean /= double(n);
  mean_sq /= double(n);
  // Uniform on the sphere: mean 0, E[x^2] = 1/3 per axis (standard errors ~0.003).
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(mean[a], 0.0, 0.015) << a;
    EXPECT_NEAR(mean_sq[a], 1.0 / 3.0, 0.015) << a;
    // Origins reach close to every face of the enlarged box.
    EXPECT_LT(seen.lo[a] - allowed.lo[a], 0.01f * (allowed.hi[a] - allowed.lo[a])) << a;
    EXPECT_LT(allowed.hi[a] - seen.hi[a], 0.01f * (allowed.hi[a] - allowed.lo[a])) << a;
  }
}

TEST(RaySets, BadInputsAreInputErrors) {
  EXPECT_THROW(random_rays(Bounds3(), 10, 1), InputError);
  Geometry spheres_only;
  spheres_only.add_sphere(Sphere{});
  EXPECT_THROW(edge_rays(spheres_only, 10, 1), InputError);
  EXPECT_THROW(edge_targets(Geometry(), 10, 1), InputError);
  EXPECT_TRUE(random_rays(kBox, 0, 1).empty());
}

// Distance of x to the line through a and b, in double.
double distance_to_line(const glm::dvec3& x, const glm::dvec3& a, const glm::dvec3& b) {
  glm::dvec3 ab = b - a;
  return glm::length(glm::cross(x - a, ab)) / glm::length(ab);
}

// Even targets are mesh vertices (bit-exact); odd targets lie on an edge line, between its ends, to within
// the rounding of their construction; the rays are aimed at them (origin + direction = target at t = 1).
TEST(RaySets, EdgeTargetsLieOnVerticesAndEdges) {
  Geometry g;
  g.add_sphere(Sphere{glm::vec3(5.f), 1.f});  // non-triangles are skipped
  add_to_geometry(make_icosphere(1, glm::vec3(100.f, -50.f, 20.f), 3.f), g);
  const size_t n = 4000;
  std::vector<glm::vec3> targets = edge_targets(g, n, 11);
  std::vector<Ray> rays = edge_rays(g, n, 11);
  Bounds3 allowed = ray_origin_bounds(g.bounds());
  const double tolerance = 4 * gamma(1) * 120.0;  // a few roundings at coordinates ~100
  int on_edges = 0;
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3& x = targets[i];
    bool at_vertex = false, on_edge = false;
    for (uint32_t id = 1; id < g.size(); ++id) {
      for (int k = 0; k < 3; ++k) {
        glm::vec3 a = g.vertex(id, k), b = g.vertex(id, (k + 1) % 3);
        at_vertex = at_vertex || x == a;
        double f = glm::dot(glm::dvec3(x) - glm::dvec3(a), glm::dvec3(b) - glm::dvec3(a)) /
                   glm::dot(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(b) - glm::dvec3(a));
        on_edge = on_edge || (f > 0.05 && f < 0.95 &&
                              distance_to_line(glm::dvec3(x), glm::dvec3(a), glm::dvec3(b)) <= tolerance);
      }
    }
    if (i % 2 == 0) {
      ASSERT_TRUE(at_vertex) << i;
    } else {
      ASSERT_TRUE(on_edge) << i;
      ++on_edges;
    }
    ASSERT_TRUE(allowed.contains(rays[i].origin)) << i;
    ASSERT_LE(glm::length(glm::dvec3(rays[i].origin) + glm::dvec3(rays[i].direction) - glm::dvec3(x)),
              tolerance);
    ASSERT_EQ(rays[i].tmin, 0.f);
    ASSERT_EQ(rays[i].tmax, kInfinity);
  }
  EXPECT_EQ(on_edges, int(n / 2));
  // Deterministic by seed.
  std::vector<Ray> again = edge_rays(g, n, 11), other = edge_rays(g, n, 12);
  int same_as_other_seed = 0;
  for (size_t i = 0; i < n; ++i) {
    ASSERT_TRUE(same_bits(rays[i], again[i]));
    same_as_other_seed += same_bits(rays[i], other[i]);
  }
  EXPECT_EQ(same_as_other_seed, 0);
}

// The stress set against the closed, convex icosphere with the watertight test. Whether a ray aimed at a
// point x of the surface must pass through the mesh at x is decided by the faces that contain x (outward
// normals n_i): if the origin is in front of all of them the ray enters at x; if behind all of them it leaves
// at x (after entering elsewhere). Either way one of the faces containing x must report the hit: a leak
// there would go unnoticed by "hits something", since the ray also meets the far side. If the origin is in
// front of some and behind others, the ray only grazes the mesh at x (the plane through the origin and the
// edge supports the mesh) and may legitimately pass on either side.
TEST(RaySets, EdgeRaysHitTheIcosphereUnlessTheyGraze) {
  const glm::vec3 centre(0.3f, -0.2f, 0.1f);
  Geometry g;
  add_to_geometry(make_icosphere(2, centre, 1.f), g);
  const size_t n = 20000;
  std::vector<Ray> rays = edge_rays(g, n, 3);
  std::vector<glm::vec3> targets = edge_targets(g, n, 3);
  int must_hit = 0, leaks = 0, grazing = 0, from_outside = 0;
  for (size_t i = 0; i < n; ++i) {
    const Ray& r = rays[i];
    glm::dvec3 x(targets[i]), o(r.origin);
    from_outside += glm::length(o - glm::dvec3(centre)) > 1.0;
    int front = 0, back = 0, unsure = 0;
    std::vector<uint32_t> containing;
    for (uint32_t id = 0; id < g.size(); ++id) {
      glm::dvec3 p0(g.vertex(id, 0)), p1(g.vertex(id, 1)), p2(g.vertex(id, 2));
      glm::dvec3 nrm = glm::cross(p1 - p0, p2 - p0);
      double area2 = glm::dot(nrm, nrm);
      // Does the face contain x (within rounding)? In its plane, and barycentrics >= 0.
      if (std::fabs(glm::dot(nrm, x - p0)) > 1e-5 * std::sqrt(area2)) continue;
      double b0 = glm::dot(nrm, glm::cross(p1 - x, p2 - x)) / area2;
      double b1 = glm::dot(nrm, glm::cross(p2 - x, p0 - x)) / area2;
      double b2 = glm::dot(nrm, glm::cross(p0 - x, p1 - x)) / area2;
      if (b0 < -1e-5 || b1 < -1e-5 || b2 < -1e-5) continue;
      containing.push_back(id);
      double side = glm::dot(nrm, o - x) / (std::sqrt(area2) * glm::length(o - x));  // cosine
      if (side > 1e-4)
        ++front;
      else if (side < -1e-4)
        ++back;
      else
        ++unsure;
    }
    ASSERT_GE(containing.size(), 2u) << i;  // a vertex or an edge point: at least two faces
    if (unsure || (front && back)) {
      ++grazing;
      continue;
    }
    ++must_hit;
    WatertightRay w(r);
    TriangleHit h;
    bool hit = false;
    for (uint32_t id : containing)
      hit = hit || intersect_triangle(w, g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), r.tmax, &h);
    leaks += !hit;
  }
  EXPECT_GT(from_outside, int(n / 2));
  EXPECT_GT(must_hit, int(n * 3 / 4));
  EXPECT_EQ(leaks, 0) << "of " << must_hit << " rays that must hit (" << grazing << " grazing ones skipped)";
}

}  // namespace
}  // namespace raystep
