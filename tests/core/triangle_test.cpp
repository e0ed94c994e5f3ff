// triangle.h: the watertight ray-triangle test (Woop, Benthin and Wald 2013). Analytic t and barycentrics,
// both windings, the open interval (tmin, tmax), degenerate triangles and invalid rays, large and small
// coordinates, the accuracy of t, and watertightness: rays from inside a closed icosphere aimed exactly at
// its shared edges and vertices must never leak. triangle_moller.h (the non-watertight reference) is checked
// against it on ordinary rays. Hard cases (slivers, needles, long thin triangles seen from nearby, rays through
// edges, origins on the plane) are checked against exact rational arithmetic (exact_reference.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raystep/geometry/icosphere.h"
#include "raystep/geometry/triangle.h"
#include "raystep/geometry/triangle_moller.h"
#include "raystep/render/camera.h"
#include "raystep/scene/geometry.h"
#include "raystep/io/scene_loader.h"
#include "raystep/scene/ray_sets.h"
#include "exact_reference.h"

namespace raystep {
namespace {

Ray make_ray(glm::vec3 o, glm::vec3 d, float tmin = 0.f, float tmax = kInfinity) {
  Ray r;
  r.origin = o;
  r.direction = d;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

const glm::vec3 kP0(0.f, 0.f, 0.f), kP1(1.f, 0.f, 0.f), kP2(0.f, 1.f, 0.f);

TEST(Triangle, AnalyticDistanceAndBarycentrics) {
  TriangleHit h;
  ASSERT_TRUE(intersect_triangle(make_ray({0.25f, 0.25f, 2.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));
  EXPECT_FLOAT_EQ(h.t, 2.f);
  EXPECT_NEAR(h.b0, 0.5f, 1e-7);
  EXPECT_NEAR(h.b1, 0.25f, 1e-7);
  EXPECT_NEAR(h.b2, 0.25f, 1e-7);
  // Oblique, unnormalised direction: from (1, 1, 3) along (-0.8, -0.4, -3) reaches z = 0 at t = 1,
  // at (0.2, 0.6, 0): b1 = x = 0.2, b2 = y = 0.6.
  ASSERT_TRUE(intersect_triangle(make_ray({1.f, 1.f, 3.f}, {-0.8f, -0.4f, -3.f}), kP0, kP1, kP2, &h));
  EXPECT_NEAR(h.t, 1.f, 1e-6);
  EXPECT_NEAR(h.b1, 0.2f, 1e-6);
  EXPECT_NEAR(h.b2, 0.6f, 1e-6);
  EXPECT_NEAR(h.b0 + h.b1 + h.b2, 1.f, 1e-6);
  glm::vec3 err;
  glm::vec3 p = triangle_point(h, kP0, kP1, kP2, &err);
  EXPECT_NEAR(p.x, 0.2f, 1e-6);
  EXPECT_NEAR(p.y, 0.6f, 1e-6);
  EXPECT_NEAR(p.z, 0.f, 1e-6);
  EXPECT_GT(err.x, 0.f);
  EXPECT_EQ(triangle_normal(kP0, kP1, kP2), glm::vec3(0.f, 0.f, 1.f));
}

// Both windings and both sides: no culling; the barycentrics follow the vertex order.
TEST(Triangle, BothWindingsAndBothSides) {
  for (float side : {1.f, -1.f}) {
    Ray r = make_ray({0.1f, 0.3f, 2.f * side}, {0.f, 0.f, -side});
    TriangleHit h, g;
    ASSERT_TRUE(intersect_triangle(r, kP0, kP1, kP2, &h));
    ASSERT_TRUE(intersect_triangle(r, kP0, kP2, kP1, &g));
    EXPECT_EQ(h.t, g.t);
    EXPECT_FLOAT_EQ(h.t, 2.f);
    EXPECT_NEAR(h.b1, 0.1f, 1e-6);
    EXPECT_NEAR(h.b2, 0.3f, 1e-6);
    EXPECT_NEAR(g.b1, 0.3f, 1e-6);  // swapped with the vertices
    EXPECT_NEAR(g.b2, 0.1f, 1e-6);
  }
}

// tmin < t < tmax, both ends open; t = 2 is exact here.
TEST(Triangle, OpenInterval) {
  TriangleHit h;
  const glm::vec3 o(0.25f, 0.25f, 2.f), d(0.f, 0.f, -1.f);
  EXPECT_FALSE(intersect_triangle(make_ray(o, d, 0.f, 2.f), kP0, kP1, kP2, &h));
  EXPECT_TRUE(intersect_triangle(make_ray(o, d, 0.f, next_float_up(2.f)), kP0, kP1, kP2, &h));
  EXPECT_FALSE(intersect_triangle(make_ray(o, d, 2.f, 10.f), kP0, kP1, kP2, &h));
  EXPECT_TRUE(intersect_triangle(make_ray(o, d, next_float_down(2.f), 10.f), kP0, kP1, kP2, &h));
  // The tmax argument of the prepared form overrides the ray's (accelerators shrink it).
  WatertightRay w(make_ray(o, d));
  EXPECT_FALSE(intersect_triangle(w, kP0, kP1, kP2, 1.5f, &h));
  EXPECT_TRUE(intersect_triangle(w, kP0, kP1, kP2, 2.5f, &h));
  // Behind the origin.
  EXPECT_FALSE(intersect_triangle(make_ray(o, -d), kP0, kP1, kP2, &h));
  // Origin in the plane, ray leaving it: t = 0 is not in (0, tmax).
  EXPECT_FALSE(intersect_triangle(make_ray({0.25f, 0.25f, 0.f}, {0.f, 0.f, 1.f}), kP0, kP1, kP2, &h));
}

// Edges and vertices belong to the triangle (closed), so a ray exactly through them hits.
TEST(Triangle, EdgesAndVerticesAreInside) {
  TriangleHit h;
  ASSERT_TRUE(intersect_triangle(make_ray({0.5f, 0.f, 1.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));
  EXPECT_EQ(h.b2, 0.f);
  EXPECT_NEAR(h.b1, 0.5f, 1e-7);
  ASSERT_TRUE(
      intersect_triangle(make_ray({0.5f, 0.5f, 1.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));  // hypotenuse
  EXPECT_EQ(h.b0, 0.f);
  ASSERT_TRUE(intersect_triangle(make_ray({1.f, 0.f, 1.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));  // vertex
  EXPECT_EQ(h.b1, 1.f);
  EXPECT_FALSE(intersect_triangle(make_ray({0.5f, -1e-6f, 1.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));
  EXPECT_FALSE(intersect_triangle(make_ray({1.f + 1e-6f, 0.f, 1.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));
}

TEST(Triangle, DegenerateTrianglesAndInvalidRaysMiss) {
  TriangleHit h;
  Ray down = make_ray({0.25f, 0.25f, 1.f}, {0.f, 0.f, -1.f});
  EXPECT_FALSE(intersect_triangle(down, kP0, kP1, glm::vec3(2.f, 0.f, 0.f), &h));  // collinear
  EXPECT_FALSE(intersect_triangle(down, kP0, kP0, kP0, &h));                       // a point
  Ray through_point = make_ray({0.f, 0.f, 1.f}, {0.f, 0.f, -1.f});
  EXPECT_FALSE(intersect_triangle(through_point, kP0, kP0, kP0, &h));
  Ray along_segment = make_ray({0.5f, 0.f, 1.f}, {0.f, 0.f, -1.f});
  EXPECT_FALSE(intersect_triangle(along_segment, kP0, kP1, glm::vec3(2.f, 0.f, 0.f), &h));
  // A ray lying in the triangle's plane (edge-on): the triangle has no area seen from it.
  EXPECT_FALSE(intersect_triangle(make_ray({-1.f, 0.25f, 0.f}, {1.f, 0.f, 0.f}), kP0, kP1, kP2, &h));
  const float nan = std::nanf("");
  EXPECT_FALSE(intersect_triangle(make_ray({nan, 0.25f, 1.f}, {0.f, 0.f, -1.f}), kP0, kP1, kP2, &h));
  EXPECT_FALSE(intersect_triangle(make_ray({0.25f, 0.25f, 1.f}, {0.f, nan, -1.f}), kP0, kP1, kP2, &h));
  EXPECT_FALSE(intersect_triangle(make_ray({0.25f, 0.25f, 1.f}, {0.f, 0.f, 0.f}), kP0, kP1, kP2, &h));
  EXPECT_FALSE(
      intersect_triangle(make_ray({0.25f, 0.25f, 1.f}, {0.f, 0.f, -1.f}, nan, 5.f), kP0, kP1, kP2, &h));
  EXPECT_FALSE(
      intersect_triangle(make_ray({0.25f, 0.25f, 1.f}, {0.f, 0.f, -1.f}, 0.f, nan), kP0, kP1, kP2, &h));
  EXPECT_FALSE(intersect_triangle(make_ray({0.25f, 0.25f, 1.f}, {0.f, 0.f, -kInfinity}), kP0, kP1, kP2, &h));
}

// The same triangle, scaled by s and moved to s * (3, -2, 5): t is scale-free, barycentrics the same.
TEST(Triangle, LargeAndSmallCoordinates) {
  for (float s : {1e-4f, 1e-2f, 1.f, 1e3f, 1e6f}) {
    glm::vec3 c = s * glm::vec3(3.f, -2.f, 5.f);
    glm::vec3 p0 = c + s * kP0, p1 = c + s * kP1, p2 = c + s * kP2;
    glm::vec3 o = c + s * glm::vec3(0.25f, 0.5f, 2.f);
    TriangleHit h;
    ASSERT_TRUE(intersect_triangle(make_ray(o, s * glm::vec3(0.f, 0.f, -1.f)), p0, p1, p2, &h)) << s;
    EXPECT_NEAR(h.t, 2.f, 2e-6) << s;
    EXPECT_NEAR(h.b1, 0.25f, 1e-5) << s;
    EXPECT_NEAR(h.b2, 0.5f, 1e-5) << s;
    // Unit-length direction: t is the distance, 2 s.
    ASSERT_TRUE(intersect_triangle(make_ray(o, glm::vec3(0.f, 0.f, -1.f)), p0, p1, p2, &h)) << s;
    EXPECT_NEAR(h.t, 2.f * s, 2e-6 * s) << s;
    // Oblique: aimed at the point with barycentrics (0.5, 0.3, 0.2) from off to the side.
    glm::vec3 target = 0.5f * p0 + 0.3f * p1 + 0.2f * p2;
    glm::vec3 from = c + s * glm::vec3(-1.f, 2.f, 1.5f);
    ASSERT_TRUE(intersect_triangle(make_ray(from, target - from), p0, p1, p2, &h)) << s;
    EXPECT_NEAR(h.t, 1.f, 1e-5) << s;
    EXPECT_NEAR(h.b1, 0.3f, 1e-5) << s;
    EXPECT_NEAR(h.b2, 0.2f, 1e-5) << s;
    // Beside it by 1 % of its size: a miss at every scale.
    EXPECT_FALSE(intersect_triangle(make_ray(c + s * glm::vec3(-0.01f, 0.5f, 2.f), glm::vec3(0.f, 0.f, -1.f)),
                                    p0, p1, p2, &h))
        << s;
  }
}

// The direction need not be normalised (ray.h): scaling it by k scales t by 1/k and changes nothing else.
// Regression: the conservative t > 0 bound once mixed scaled and unscaled z (as pbrt-v4's code does), so
// short directions (e.g. d = target - origin at small scales) rejected every hit on small triangles.
TEST(Triangle, DirectionLengthDoesNotMatter) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.05f, 0.9f);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    float s = std::pow(10.f, float(int(rng() % 11) - 4));  // triangle size and distance, 1e-4 .. 1e6
    glm::vec3 c = s * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p0 = c + s * glm::vec3(u(rng), u(rng), u(rng)), p1 = c + s * glm::vec3(u(rng), u(rng), u(rng)),
              p2 = c + s * glm::vec3(u(rng), u(rng), u(rng));
    float b1 = w(rng), b2 = w(rng) * (1.f - b1);
    glm::vec3 o = c + 4.f * s * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 d = glm::normalize((1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2 - o);
    if (std::fabs(glm::dot(glm::normalize(triangle_normal(p0, p1, p2)), d)) < 0.1f)
      continue;  // t ill-conditioned
    TriangleHit h;
    bool reference = intersect_triangle(make_ray(o, d), p0, p1, p2, &h);
    hits += reference;
    for (float k : {1e-6f, 1e-3f, 0.5f, 4.f, 1e3f, 1e6f}) {  // powers of two would be exact; these are not
      TriangleHit hk;
      ASSERT_EQ(intersect_triangle(make_ray(o, k * d), p0, p1, p2, &hk), reference) << i << " k " << k;
      if (reference) ASSERT_NEAR(hk.t * k, h.t, 1e-5f * h.t) << i << " k " << k;
    }
  }
  EXPECT_GT(hits, 3500);
}

// t against the exact distance to the plane (double arithmetic on the float inputs), for random triangles
// and rays at random scales: the relative error stays at the level of a few dozen roundings.
TEST(Triangle, DistanceAccuracy) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.05f, 0.9f);
  double worst = 0;
  int hits = 0;
  for (int i = 0; i < 50000; ++i) {
    float s = std::pow(10.f, float(int(rng() % 11) - 4));  // 1e-4 .. 1e6
    glm::vec3 c = s * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p0 = c + s * glm::vec3(u(rng), u(rng), u(rng)), p1 = c + s * glm::vec3(u(rng), u(rng), u(rng)),
              p2 = c + s * glm::vec3(u(rng), u(rng), u(rng));
    float b1 = w(rng), b2 = w(rng) * (1.f - b1);
    glm::vec3 target = (1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
    glm::vec3 o = c + 4.f * s * glm::vec3(u(rng), u(rng), u(rng));
    glm::dvec3 d(target - o);
    glm::dvec3 n = glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
    double cos_angle = std::fabs(glm::dot(glm::normalize(n), glm::normalize(d)));
    if (cos_angle < 0.1) continue;  // nearly edge-on: t is ill-conditioned for any method
    TriangleHit h;
    if (!intersect_triangle(make_ray(o, target - o), p0, p1, p2, &h)) continue;
    ++hits;
    double t_exact = glm::dot(n, glm::dvec3(p0) - glm::dvec3(o)) / glm::dot(n, d);
    worst = std::fmax(worst, std::fabs(h.t - t_exact) / t_exact);
  }
  EXPECT_GT(hits, 40000);
  EXPECT_LT(worst, 64 * gamma(1)) << "worst relative error of t";
}

// Möller–Trumbore agrees with the watertight test away from edges (same t, same barycentrics).
TEST(Triangle, MollerTrumboreAgreesAwayFromEdges) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.05f, 0.9f);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng)), p2(u(rng), u(rng), u(rng));
    glm::vec3 o = 3.f * glm::vec3(u(rng), u(rng), u(rng));
    float b1 = w(rng), b2 = w(rng) * (1.f - b1);
    Ray r = make_ray(o, (1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2 - o);
    if (i % 2) r.direction = glm::vec3(u(rng), u(rng), u(rng));  // mostly misses
    // Skip nearly edge-on views, where both methods are ill-conditioned.
    glm::vec3 n = glm::normalize(triangle_normal(p0, p1, p2));
    if (std::fabs(glm::dot(n, glm::normalize(r.direction))) < 0.1f) continue;
    TriangleHit a, b;
    bool ha = intersect_triangle(r, p0, p1, p2, &a), hb = intersect_triangle_moller(r, p0, p1, p2, &b);
    if (ha && hb) {
      ++compared;
      ASSERT_NEAR(a.t, b.t, 1e-4f * a.t);
      ASSERT_NEAR(a.b1, b.b1, 1e-4f);
      ASSERT_NEAR(a.b2, b.b2, 1e-4f);
    } else if (ha != hb) {
      // Only near an edge may the two disagree.
      const TriangleHit& hit = ha ? a : b;
      ASSERT_LT(std::fmin(hit.b0, std::fmin(hit.b1, hit.b2)), 1e-4f);
    }
  }
  EXPECT_GT(compared, 9000);
}

// moller_trumbore_values (the debugger's "why") computes the very values of the test: on rays aimed at edges,
// vertices and near misses, it rejects exactly where intersect_triangle_moller does, and on a hit gives its t, u, v.
TEST(Triangle, MollerTrumboreValuesAreTheTestsValues) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  int hits = 0, misses = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng)), p2(u(rng), u(rng), u(rng));
    glm::vec3 o = 3.f * glm::vec3(u(rng), u(rng), u(rng));
    // A point on an edge (i % 3 == 0), at a vertex (1) or anywhere near the triangle (2).
    float b1 = i % 3 == 1 ? 0.f : w(rng), b2 = i % 3 == 0 ? 1.f - b1 : (i % 3 == 1 ? 0.f : 1.5f * w(rng) - 0.2f);
    Ray r = make_ray(o, (1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2 - o);
    float tmax = i % 5 == 0 ? 0.5f : kInfinity;
    TriangleHit h;
    bool hit = intersect_triangle_moller(r, p0, p1, p2, tmax, &h);
    MollerTrumboreValues m = moller_trumbore_values(r, p0, p1, p2, tmax);
    ASSERT_EQ(hit, m.failed == nullptr) << i << " " << (m.failed ? m.failed : "hit");
    if (hit) {
      ++hits;
      EXPECT_EQ(h.t, m.t);
      EXPECT_EQ(h.b1, m.u);
      EXPECT_EQ(h.b2, m.v);
    } else {
      ++misses;
    }
  }
  EXPECT_GT(hits, 3000);
  EXPECT_GT(misses, 3000);
}

// Lesson 14's scene (scenes/leak.json): the rays of pixels (29, 29) and (33, 19) pass within rounding of a front
// edge of the tilted octahedron. By brute force over all primitives, Möller–Trumbore rejects both triangles that
// share the edge and finds the red wall through the closed solid; the watertight test finds the octahedron.
TEST(Triangle, LeakSceneLeaksUnderMollerTrumboreOnly) {
  Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/leak.json");
  const Geometry& g = scene.geometry;
  ProjectiveCamera camera(scene.camera, scene.render.width, scene.render.height);
  for (auto [px, py] : {std::pair{29, 29}, std::pair{33, 19}}) {
    Ray r = camera.generate(float(px) + 0.5f, float(py) + 0.5f);
    uint32_t watertight = ~0u, moller = ~0u;
    float t_watertight = r.tmax, t_moller = r.tmax;
    for (uint32_t id = 0; id < g.size(); ++id) {
      TriangleHit h;
      if (intersect_triangle(WatertightRay(r), g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), t_watertight, &h))
        t_watertight = h.t, watertight = id;
      if (intersect_triangle_moller(r, g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), t_moller, &h))
        t_moller = h.t, moller = id;
    }
    ASSERT_NE(watertight, ~0u);
    ASSERT_NE(moller, ~0u);
    EXPECT_EQ(g.objects()[g.object_of(watertight)].name, "tilted octahedron") << px << "," << py;
    EXPECT_EQ(g.objects()[g.object_of(moller)].name, "red wall") << px << "," << py;
  }
}

// Any hit among all triangles of g (brute force), with the watertight test.
bool hits_anything(const Geometry& g, const Ray& r) {
  WatertightRay w(r);
  TriangleHit h;
  for (uint32_t id = 0; id < g.size(); ++id)
    if (intersect_triangle(w, g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), r.tmax, &h)) return true;
  return false;
}

// Watertightness (the property the algorithm is named for): a closed mesh hit from inside cannot be missed.
// Rays from the centre and from random interior points, aimed exactly at shared vertices and at points on
// shared edges: ZERO leaks. Three placements: unit sphere at the origin; radius 1000 far from the origin;
// radius 1e-3 off the origin.
TEST(Triangle, WatertightNoLeaksThroughSharedEdgesAndVertices) {
  struct Case {
    glm::vec3 centre;
    float radius;
    int subdivisions;
    size_t rays;
  };
  const Case cases[] = {{glm::vec3(0.f), 1.f, 2, 100000},
                        {glm::vec3(1e5f, -3e4f, 2e5f), 1000.f, 2, 25000},
                        {glm::vec3(0.5f, 0.25f, -0.75f), 1e-3f, 1, 25000}};
  for (const Case& c : cases) {
    Geometry g;
    add_to_geometry(make_icosphere(c.subdivisions, c.centre, c.radius), g);
    std::vector<glm::vec3> targets = edge_targets(g, c.rays, 17);
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    size_t leaks = 0;
    for (size_t i = 0; i < targets.size(); ++i) {
      glm::vec3 origin = c.centre;
      if (i % 4 != 0) {  // a random point in the ball of half the radius
        glm::vec3 v;
        do v = glm::vec3(u(rng), u(rng), u(rng));
        while (glm::dot(v, v) > 1.f);
        origin = c.centre + 0.5f * c.radius * v;
      }
      Ray r = make_ray(origin, targets[i] - origin);
      if (!hits_anything(g, r)) ++leaks;
    }
    EXPECT_EQ(leaks, 0u) << "radius " << c.radius << " at " << c.centre.x << ", " << g.size() << " triangles";
  }
}

// The ray: a long thin side of a prism (20 x 0.001) seen from 3 units away. The loose error bound on t
// (delta_t = 3.34 for t = 3.08) made the test reject this hit; in rational arithmetic it is a hit at t = 3.0834851
// with barycentrics (b0, b1, b2) about (0.064, 0.189, 0.748), well inside (the issue lists them starting at b2).
TEST(Triangle, LongThinTriangleSeenFromNearbyIsHit) {
  const glm::vec3 p0(-10.f, -0.0067148944f, 0.6011051f), p1(10.f, -0.0057148947f, 0.6011051f),
      p2(10.f, -0.0077148946f, 0.6031051f);
  Ray r = make_ray({11.153518f, 1.0161176f, -1.0f}, {-0.78722286f, -0.3318944f, 0.5197367f});
  test::ExactHit exact = test::exact_ray_triangle(r, p0, p1, p2);
  ASSERT_TRUE(exact.hit);
  EXPECT_NEAR(exact.t.get_d(), 3.0834851, 1e-6);
  TriangleHit h;
  ASSERT_TRUE(intersect_triangle(r, p0, p1, p2, &h));
  EXPECT_NEAR(h.t, 3.0834851f, 1e-5f);
  EXPECT_NEAR(h.b0, exact.b[0].get_d(), 1e-5);
  EXPECT_NEAR(h.b1, exact.b[1].get_d(), 1e-5);
  EXPECT_NEAR(h.b2, exact.b[2].get_d(), 1e-5);
  EXPECT_NEAR(h.b0, 0.064f, 1e-3f);
  EXPECT_NEAR(h.b1, 0.189f, 1e-3f);
  EXPECT_NEAR(h.b2, 0.748f, 1e-3f);
}

// Hard cases against exact rational arithmetic: the test's hit or miss is the exact one on every ray (tmax =
// +inf, so only the edges and t > tmin decide), and every hit has barycentrics >= 0 and a point (triangle_point)
// whose documented error box reaches the exact plane of the triangle. Slivers (a vertex within 1e-4..1e-7 of the
// opposite edge), needles (two vertices within that of each other), long thin triangles (length : width up to
// 10^5) seen from nearby, at scales 1e-3 to 1e4 and up to 1e4 sizes from the origin; rays aimed at interior
// points, at rounded points of edges and at vertices; origins on or near the triangle's plane; nonzero tmin.
TEST(Triangle, HardCasesAgreeWithExactArithmetic) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  int hits = 0, misses = 0, disagreements = 0, off_plane = 0, negative_barycentric = 0, origins_on_plane = 0;
  for (int i = 0; i < 60000; ++i) {
    float scale = std::pow(10.f, float(int(rng() % 8) - 3));  // 1e-3 .. 1e4
    glm::vec3 c = (i % 2 ? 0.f : 1e4f) * scale * glm::vec3(u(rng), u(rng), u(rng));
    float thin = std::pow(10.f, -float(2 + rng() % 6));  // 1e-2 .. 1e-7
    glm::vec3 p0 = c + scale * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p1 = c + scale * glm::vec3(u(rng), u(rng), u(rng)), p2;
    switch (i % 3) {
      case 0:  // sliver: p2 near the edge p0 p1
        p2 = p0 + (p1 - p0) * w(rng) + thin * scale * glm::vec3(u(rng), u(rng), u(rng));
        break;
      case 1:  // needle: p1 and p2 close together
        p2 = p1 + thin * scale * glm::vec3(u(rng), u(rng), u(rng));
        break;
      default:  // ordinary
        p2 = c + scale * glm::vec3(u(rng), u(rng), u(rng));
    }
    float b1 = w(rng), b2 = w(rng);
    if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
    glm::vec3 target = (1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
    if (i % 5 == 1) target = p0 + w(rng) * (p1 - p0);  // a rounded point of an edge
    if (i % 5 == 2) target = p2;                        // a vertex
    // Origins from far (100 sizes) to very near the triangle (1e-6 of its size), some exactly on a vertex's
    // plane through the target, which puts them on or next to the triangle's plane.
    float distance = scale * std::pow(10.f, float(int(rng() % 9) - 6));
    glm::vec3 origin = target + distance * glm::vec3(u(rng), u(rng), u(rng));
    if (i % 7 == 3) {
      origin = p0 + w(rng) * (p1 - p0) + w(rng) * (p2 - p0) * 0.5f;  // (nearly) in the plane
      ++origins_on_plane;
    }
    glm::vec3 dir = target - origin;
    if (i % 4 == 3) dir = glm::vec3(u(rng), u(rng), u(rng));  // any direction
    float tmin = i % 6 == 5 ? w(rng) * 0.5f : 0.f;
    Ray r = make_ray(origin, dir, tmin);
    test::ExactHit exact = test::exact_ray_triangle(r, p0, p1, p2);
    TriangleHit h;
    bool hit = intersect_triangle(r, p0, p1, p2, &h);
    if (hit != exact.hit) {
      ++disagreements;
      if (disagreements <= 3)
        ADD_FAILURE() << "case " << i << ": test says " << hit << ", exact " << exact.hit << " t* " << exact.t.get_d()
                      << " edges " << exact.edge[0] << exact.edge[1] << exact.edge[2] << " tmin " << tmin << " kind "
                      << i % 3 << " scale " << scale << " thin " << thin << " dist " << distance;
      continue;
    }
    if (!hit) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_GT(h.t, r.tmin);
    negative_barycentric += (h.b0 < 0.f) | (h.b1 < 0.f) | (h.b2 < 0.f);
    glm::vec3 err;
    glm::vec3 p = triangle_point(h, p0, p1, p2, &err);
    // The box p +- err meets the exact plane n.(x - p0) = 0 when |n.(p - p0)| <= sum |n_i| err_i.
    test::QVec n = test::cross(test::sub(test::to_q(p1), test::to_q(p0)), test::sub(test::to_q(p2), test::to_q(p0)));
    mpq_class distance_n = abs(test::dot(n, test::sub(test::to_q(p), test::to_q(p0))));
    mpq_class reach = abs(n[0]) * mpq_class(double(err.x)) + abs(n[1]) * mpq_class(double(err.y)) +
                      abs(n[2]) * mpq_class(double(err.z));
    off_plane += distance_n > reach;
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_EQ(negative_barycentric, 0);
  EXPECT_EQ(off_plane, 0);
  // The mix is hard and balanced: many hits and many misses, origins on the plane included.
  EXPECT_GT(hits, 15000);
  EXPECT_GT(misses, 15000);
  EXPECT_GT(origins_on_plane, 8000);
}

}  // namespace
}  // namespace raystep
