// bounds.h: the robust slab test. Analytic entry/exit distances; +0 and -0 direction components; rays lying
// in a slab's plane; parallel rays outside with tmax = +inf; NaN rays; and Ize's conservativeness: a ray
// that hits a triangle also hits the triangle's tight box.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/triangle.h"

namespace raystep {
namespace {

const Bounds3 kUnitBox(glm::vec3(-1.f), glm::vec3(1.f));

Ray make_ray(glm::vec3 o, glm::vec3 d, float tmin = 0.f, float tmax = kInfinity) {
  Ray r;
  r.origin = o;
  r.direction = d;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

TEST(Bounds, BuildingAndQueries) {
  Bounds3 b;
  EXPECT_TRUE(b.empty());
  b.extend(glm::vec3(1.f, 2.f, 3.f));
  b.extend(glm::vec3(-1.f, 0.f, 5.f));
  EXPECT_FALSE(b.empty());
  EXPECT_EQ(b.lo, glm::vec3(-1.f, 0.f, 3.f));
  EXPECT_EQ(b.hi, glm::vec3(1.f, 2.f, 5.f));
  EXPECT_NEAR(b.surface_area(), 2 * (4 + 4 + 4), 1e-6);
  EXPECT_EQ(b.center(), glm::vec3(0.f, 1.f, 4.f));
  EXPECT_TRUE(b.contains(glm::vec3(1.f, 2.f, 5.f)));  // closed box
  EXPECT_FALSE(b.contains(glm::vec3(1.f, 2.f, 5.0001f)));
}

TEST(Bounds, EntryAndExitDistances) {
  float t0, t1;
  ASSERT_TRUE(intersect_slabs(kUnitBox, make_ray({-5.f, 0.f, 0.f}, {1.f, 0.f, 0.f}), &t0, &t1));
  EXPECT_NEAR(t0, 4.f, 1e-6);
  EXPECT_NEAR(t1, 6.f, 1e-5);
  EXPECT_GE(t1, 6.f);  // Ize's factor only ever enlarges the exit
  // Oblique, unnormalised direction: enters through x = -1 at t = 1, leaves through y = 1 at t = 1.5.
  ASSERT_TRUE(intersect_slabs(kUnitBox, make_ray({-3.f, -2.f, 0.5f}, {2.f, 2.f, 0.f}), &t0, &t1));
  EXPECT_NEAR(t0, 1.f, 1e-6);
  EXPECT_NEAR(t1, 1.5f, 1e-6);
  // Origin inside: the entry is clamped to tmin.
  ASSERT_TRUE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {0.f, 0.f, -0.5f}), &t0, &t1));
  EXPECT_EQ(t0, 0.f);
  EXPECT_NEAR(t1, 2.f, 1e-6);
  // tmin/tmax clip the interval.
  ASSERT_TRUE(intersect_slabs(kUnitBox, make_ray({-5.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 4.5f, 5.5f), &t0, &t1));
  EXPECT_EQ(t0, 4.5f);
  EXPECT_EQ(t1, 5.5f);
}

TEST(Bounds, Misses) {
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({-5.f, 0.f, 0.f}, {-1.f, 0.f, 0.f})));  // box behind
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({-5.f, 3.f, 0.f}, {1.f, 0.1f, 0.f})));  // passes above
  EXPECT_FALSE(
      intersect_slabs(kUnitBox, make_ray({-5.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 0.f, 3.9f)));  // too short
  EXPECT_FALSE(
      intersect_slabs(kUnitBox, make_ray({-5.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 6.1f, 9.f)));  // starts after
  EXPECT_FALSE(intersect_slabs(Bounds3(), make_ray({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f})));    // empty box
}

// A zero direction component of either sign: the sign bit picks the planes, and the answers are identical.
TEST(Bounds, PlusAndMinusZeroDirectionsAgree) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-3.f, 3.f);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    glm::vec3 o(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
    int axis = int(rng() % 3);
    if (i % 4 == 0) o[axis] = (i % 8 == 0) ? 1.f : -1.f;  // sometimes in the face plane as well
    glm::vec3 dp = d, dm = d;
    dp[axis] = 0.f;
    dm[axis] = -0.f;
    float tp0 = -1, tp1 = -1, tm0 = -2, tm1 = -2;
    bool hp = intersect_slabs(kUnitBox, make_ray(o, dp), &tp0, &tp1);
    bool hm = intersect_slabs(kUnitBox, make_ray(o, dm), &tm0, &tm1);
    ASSERT_EQ(hp, hm) << i;
    if (hp) {
      ASSERT_EQ(tp0, tm0);
      ASSERT_EQ(tp1, tm1);
      ASSERT_FALSE(std::isnan(tp0) || std::isnan(tp1));
      // Analytic check: the parallel ray is hit only if its coordinate on that axis lies in the slab.
      ASSERT_TRUE(o[axis] >= -1.f && o[axis] <= 1.f);
    }
    hits += hp;
  }
  EXPECT_GT(hits, 1000);
}

// Rays lying exactly in a face plane (0 * inf = NaN in the slab computation): the closed box is hit,
// along the face, with finite distances.
TEST(Bounds, RayLyingInAFacePlaneHits) {
  for (float sign : {1.f, -1.f}) {
    for (float zero : {0.f, -0.f}) {
      float t0 = -1, t1 = -1;
      Ray r = make_ray({-5.f, sign * 1.f, 0.f}, {1.f, zero, 0.f});  // in the plane y = +-1
      ASSERT_TRUE(intersect_slabs(kUnitBox, r, &t0, &t1)) << sign << " " << zero;
      EXPECT_NEAR(t0, 4.f, 1e-6);
      EXPECT_NEAR(t1, 6.f, 1e-5);
      // Along an edge of the box (two face planes at once).
      r = make_ray({-5.f, sign * 1.f, -1.f}, {1.f, zero, zero});
      ASSERT_TRUE(intersect_slabs(kUnitBox, r, &t0, &t1));
      EXPECT_NEAR(t0, 4.f, 1e-6);
      EXPECT_NEAR(t1, 6.f, 1e-5);
    }
  }
  // In the face plane but beside the box: a miss.
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({-5.f, 1.f, 3.f}, {1.f, 0.f, 0.f})));
  // A flat box (zero thickness, like the box of an axis-aligned triangle), hit by a ray in its plane.
  Bounds3 flat(glm::vec3(-1.f, 0.f, -1.f), glm::vec3(1.f, 0.f, 1.f));
  float t0, t1;
  ASSERT_TRUE(intersect_slabs(flat, make_ray({-2.f, 0.f, 0.f}, {1.f, -0.f, 0.f}), &t0, &t1));
  EXPECT_NEAR(t0, 1.f, 1e-6);
  EXPECT_NEAR(t1, 3.f, 1e-5);
  // ... and crossing it.
  ASSERT_TRUE(intersect_slabs(flat, make_ray({0.5f, 2.f, 0.5f}, {0.f, -1.f, 0.f}), &t0, &t1));
  EXPECT_NEAR(t0, 2.f, 1e-6);
}

// A ray parallel to a slab and outside it must miss, also with tmax = +inf (t_near = +inf there).
TEST(Bounds, ParallelRayOutsideMissesWithInfiniteTmax) {
  for (float zero : {0.f, -0.f}) {
    EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({-5.f, 2.f, 0.f}, {1.f, zero, 0.f})));
    EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({-5.f, -2.f, 0.f}, {1.f, zero, 0.f})));
    EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 2.f, 0.f}, {zero, zero, 1.f})));
    EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({5.f, 5.f, 5.f}, {zero, zero, -1.f})));
  }
  // Inside the slab, parallel, infinite tmax: a hit.
  float t0, t1;
  EXPECT_TRUE(intersect_slabs(kUnitBox, make_ray({0.f, 0.5f, 0.f}, {0.f, 0.f, 1.f}), &t0, &t1));
  EXPECT_EQ(t0, 0.f);
  EXPECT_NEAR(t1, 1.f, 1e-6);
  // tmax = +inf with the box ahead: the exit is finite.
  EXPECT_TRUE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, -10.f}, {0.f, 0.f, 1.f}), &t0, &t1));
  EXPECT_TRUE(std::isfinite(t1));
}

TEST(Bounds, InvalidRaysMiss) {
  const float nan = std::nanf("");
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({nan, 0.f, 0.f}, {1.f, 0.f, 0.f})));
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {nan, 0.f, 1.f})));
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {0.f, 0.f, 0.f})));  // no direction
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, nan, 1.f)));
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 0.f, nan)));
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({kInfinity, 0.f, 0.f}, {-1.f, 0.f, 0.f})));
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {kInfinity, 0.f, 0.f})));
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 2.f, 1.f)));  // empty
}

// Ize (JCGT 2013): the slab test must be conservative. Random thin triangles (slivers, and flat ones lying in
// an axis plane so that the tight box has zero thickness), rays aimed at points inside them: every ray that
// the triangle test hits must also hit the tight box, and the box's [t_enter, t_exit] must contain the exact
// distance to the triangle's plane (computed in double), the entry up to its own rounding (2 gamma(3) t).
// (The triangle test's own t may differ from the exact one by more: see Triangle.DistanceAccuracy.)
TEST(Bounds, ConservativeForRaysHittingTheTriangleInside) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  int triangle_hits = 0, box_misses = 0, after_exit = 0, before_entry = 0;
  double worst_late = 0;
  int exact_inside = 0;
  float worst_early = 0.f;
  for (int i = 0; i < 200000; ++i) {
    float scale = std::pow(10.f, float(int(rng() % 9) - 3));  // 1e-3 .. 1e5
    glm::vec3 c = scale * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p0 = c + scale * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p1 = c + scale * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p2;
    if (i % 3 == 0) {
      p2 = p0 + (p1 - p0) * w(rng) + scale * 1e-4f * glm::vec3(u(rng), u(rng), u(rng));  // sliver
    } else {
      p2 = c + scale * glm::vec3(u(rng), u(rng), u(rng));
    }
    if (i % 3 == 1) {  // flat in an axis plane: the box is as thin as it can be
      int axis = int(rng() % 3);
      p1[axis] = p2[axis] = p0[axis];
    }
    Bounds3 box(p0, p1);
    box.extend(p2);
    // Aim at a random point of the triangle, an edge or a vertex, from a random origin around it.
    float b1 = w(rng), b2 = w(rng);
    if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
    glm::vec3 target = (1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
    if (i % 4 == 2) target = p0 + 0.25f * (p2 - p0);  // on an edge: the tight box's face
    if (i % 4 == 3) target = p1;                      // at a vertex: often a corner of the tight box
    glm::vec3 origin = c + 3.f * scale * glm::vec3(u(rng), u(rng), u(rng));
    if (i % 5 == 0) origin[rng() % 3] = target[rng() % 3];  // some axis-parallel-ish components
    Ray r = make_ray(origin, target - origin);
    TriangleHit th;
    if (!intersect_triangle(r, p0, p1, p2, &th)) continue;
    ++triangle_hits;
    float t0, t1;
    if (!intersect_slabs(box, r, &t0, &t1)) {
      ++box_misses;
      continue;
    }
    // Exact distance to the plane of the float vertices: double cross products of float differences.
    glm::dvec3 n = glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
    double t_exact = glm::dot(n, glm::dvec3(p0) - glm::dvec3(origin)) / glm::dot(n, glm::dvec3(r.direction));
    // Only where the exact plane hit lies in the box (the triangle test settles rays near an edge exactly, so
    // this holds for every hit; the check stays as the test's own guard).
    glm::dvec3 x = glm::dvec3(origin) + t_exact * glm::dvec3(r.direction);
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside = inside && x[a] >= box.lo[a] && x[a] <= box.hi[a];
    if (!inside) continue;
    ++exact_inside;
    after_exit += t_exact > t1;
    if (t_exact < t0) {
      worst_early = std::fmax(worst_early, float((t0 - t_exact) / t0));
      before_entry += (t0 - t_exact) > 2 * gamma(3) * t0;
    }
    worst_late = std::fmax(worst_late, (t_exact - t1) / t1);
  }
  // About 139,000: a ray aimed at a rounded point of an edge or a vertex passes just beside the triangle about
  // half the time, and the triangle test settles such rays exactly.
  EXPECT_GT(triangle_hits, 130000);
  EXPECT_GT(exact_inside, 100000);
  EXPECT_EQ(box_misses, 0);
  EXPECT_EQ(after_exit, 0) << "worst relative (t - t_exit) / t_exit: " << worst_late;
  EXPECT_EQ(before_entry, 0) << "worst relative (t_enter - t) / t_enter: " << worst_early;
}

}  // namespace
}  // namespace raystep
