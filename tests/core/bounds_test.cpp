// bounds.h: the robust slab test. Analytic entry/exit distances; +0 and -0 direction components; rays lying
// in a slab's plane; parallel rays outside with tmax = +inf; NaN rays; and Ize's conservativeness: a ray
// that hits a triangle also hits the triangle's tight box.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "exact_reference.h"
#include "raystep/geometry/bounds.h"
#include "raystep/geometry/tri_box_overlap.h"
#include "raystep/geometry/triangle.h"
#include "raystep/geometry/triangle_clip.h"

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

// The slab test moves the entry towards -inf by Ize's factor: at most 2 gamma(3) of the distance, with the
// distance's own rounding and the product's, gamma(10); never past the exact entry.
void expect_entry(float t, float exact) {
  EXPECT_LE(t, exact);
  EXPECT_GE(t, exact - gamma(10) * std::fabs(exact));
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
  expect_entry(t0, 4.f);
  EXPECT_NEAR(t1, 6.f, 1e-5);
  EXPECT_GE(t1, 6.f);  // Ize's factor only ever enlarges the exit
  // Oblique, unnormalised direction: enters through x = -1 at t = 1, leaves through y = 1 at t = 1.5.
  ASSERT_TRUE(intersect_slabs(kUnitBox, make_ray({-3.f, -2.f, 0.5f}, {2.f, 2.f, 0.f}), &t0, &t1));
  expect_entry(t0, 1.f);
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
      expect_entry(t0, 4.f);
      EXPECT_NEAR(t1, 6.f, 1e-5);
      // Along an edge of the box (two face planes at once).
      r = make_ray({-5.f, sign * 1.f, -1.f}, {1.f, zero, zero});
      ASSERT_TRUE(intersect_slabs(kUnitBox, r, &t0, &t1));
      expect_entry(t0, 4.f);
      EXPECT_NEAR(t1, 6.f, 1e-5);
    }
  }
  // In the face plane but beside the box: a miss.
  EXPECT_FALSE(intersect_slabs(kUnitBox, make_ray({-5.f, 1.f, 3.f}, {1.f, 0.f, 0.f})));
  // A flat box (zero thickness, like the box of an axis-aligned triangle), hit by a ray in its plane.
  Bounds3 flat(glm::vec3(-1.f, 0.f, -1.f), glm::vec3(1.f, 0.f, 1.f));
  float t0, t1;
  ASSERT_TRUE(intersect_slabs(flat, make_ray({-2.f, 0.f, 0.f}, {1.f, -0.f, 0.f}), &t0, &t1));
  expect_entry(t0, 1.f);
  EXPECT_NEAR(t1, 3.f, 1e-5);
  // ... and crossing it.
  ASSERT_TRUE(intersect_slabs(flat, make_ray({0.5f, 2.f, 0.5f}, {0.f, -1.f, 0.f}), &t0, &t1));
  expect_entry(t0, 2.f);
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

// Ize's factor was applied as t_far *= 1 + 2 gamma(3) for every sign: a negative t_far moved inwards. A line
// (tmin = -inf) touching a box behind its origin at a corner lost the overlap: x in [-1, 0] for t in [-3, -2],
// y in [-1, 0] for t in [-2, -1], the exact interval is {-2}.
TEST(Bounds, NegativeExitDistancesStayConservative) {
  const Bounds3 box(glm::vec3(-1.f, -1.f, 0.f), glm::vec3(0.f, 0.f, 1.f));
  for (float tmin : {-kInfinity, -10.f, -2.f}) {
    float t0, t1;
    ASSERT_TRUE(intersect_slabs(box, make_ray({2.f, -2.f, 0.5f}, {1.f, -1.f, 0.f}, tmin, kInfinity), &t0, &t1))
        << tmin;
    EXPECT_LE(t0, -2.f);
    EXPECT_GE(t1, -2.f);
  }
  // The same corner ahead of the origin (positive distances) was always found.
  ASSERT_TRUE(intersect_slabs(box, make_ray({-2.f, 2.f, 0.5f}, {1.f, -1.f, 0.f})));
  // And a real miss by more than the widening (2 gamma(3) of the distances on each side) still misses: the corner
  // moved to x = -2^-18, eight float ulps of 2 in t.
  const Bounds3 moved(glm::vec3(-1.f, -1.f, 0.f), glm::vec3(-std::ldexp(1.f, -18), 0.f, 1.f));
  EXPECT_FALSE(intersect_slabs(moved, make_ray({2.f, -2.f, 0.5f}, {1.f, -1.f, 0.f}, -kInfinity, kInfinity)));
}

// Needle and slab boxes (one or two axes 1e-5 of the others) at scales 1e-3 .. 1e4, at the origin and 1e4 sizes
// away; rays aimed at points of the box, its faces, edges and corners, from outside, from a face and from
// inside, with +-0 direction components, as rays (tmin = 0), lines (tmin = -inf) and segments whose tmin or
// tmax lies near the exact entry or exit. Wherever the exact segment meets the box (rationals), the slab test
// hits and [t_enter, t_exit] contains the exact interval.
TEST(Bounds, NeverMissesAnExactOverlapAndContainsTheExactInterval) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  int overlaps = 0, misses = 0, late_entry = 0, early_exit = 0, lines = 0;
  for (int i = 0; i < 150000; ++i) {
    const float scale = std::pow(10.f, float(int(rng() % 8) - 3));  // 1e-3 .. 1e4
    glm::vec3 offset(0.f);
    if (i % 3 == 1) offset = 1e4f * scale * glm::vec3(0.7f, -0.5f, 0.5f);
    if (i % 3 == 2) offset[rng() % 3] = -1e4f * scale;
    glm::vec3 center = offset + scale * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 half = scale * (0.1f + glm::vec3(w(rng), w(rng), w(rng)));
    half[rng() % 3] *= 1e-5f;                   // a slab
    if (rng() % 2) half[rng() % 3] *= 1e-5f;    // or a needle
    const Bounds3 box(center - half, center + half);
    // The target: inside, on a face, an edge or at a corner.
    glm::vec3 target = center + half * glm::vec3(u(rng), u(rng), u(rng));
    for (int a = 0, k = int(rng() % 4); a < k; ++a) {
      int axis = int(rng() % 3);
      target[axis] = rng() % 2 ? box.lo[axis] : box.hi[axis];
    }
    glm::vec3 origin = center + 3.f * scale * glm::vec3(u(rng), u(rng), u(rng));
    if (i % 7 == 0) origin = center + half * glm::vec3(u(rng), u(rng), u(rng));  // inside
    if (i % 7 == 1) origin[rng() % 3] = box.hi[rng() % 3];                         // maybe on a face plane
    glm::vec3 d = target - origin;
    if (i % 5 == 0) {  // a zero component: the ray runs in a plane of the target
      int axis = int(rng() % 3);
      origin[axis] = target[axis];
      d[axis] = rng() % 2 ? 0.f : -0.f;
    }
    if (rng() % 2) d = -d;  // the box behind the origin: only lines and negative tmin meet it
    float tmin = 0.f, tmax = kInfinity;
    switch (rng() % 4) {
      case 0: tmin = -kInfinity; ++lines; break;
      case 1: tmin = -2.f - 4.f * w(rng); break;
      case 2: tmax = 0.5f + w(rng); break;  // about where the target is
      default: break;
    }
    if (d == glm::vec3(0.f)) continue;  // the target rounded onto the origin: no ray
    Ray r = make_ray(origin, d, tmin, tmax);
    test::Q enter, exit;
    bool enter_free, exit_free;
    if (!test::exact_slab_interval(box, origin, d, tmin, tmax, &enter, &exit, &enter_free, &exit_free)) continue;
    ++overlaps;
    float t0, t1;
    if (!intersect_slabs(box, r, &t0, &t1)) {
      if (++misses <= 5)
        ADD_FAILURE() << "miss " << i << " o " << origin.x << " " << origin.y << " " << origin.z << " d " << d.x << " "
                      << d.y << " " << d.z << " box " << box.lo.x << " " << box.lo.y << " " << box.lo.z << " "
                      << box.hi.x << " " << box.hi.y << " " << box.hi.z << " tmin " << tmin << " tmax " << tmax;
      continue;
    }
    late_entry += !enter_free && test::Q(double(t0)) > enter;
    early_exit += !exit_free && test::Q(double(t1)) < exit;
  }
  EXPECT_GT(overlaps, 60000);
  EXPECT_GT(lines, 30000);
  EXPECT_EQ(misses, 0);
  EXPECT_EQ(late_entry, 0);
  EXPECT_EQ(early_exit, 0);
}

// A thin closed prism (6 sides, 20 long and 0.02 across, also 1e5 : 1), along an axis and tilted, at scales
// 1e-3 .. 1e4, at the origin and 1e4 sizes away, against a grid of cells over its bounds: the clipped bounds of
// each triangle in each cell contain the exact clipped triangle, triangle_overlaps_box accepts every cell the
// triangle meets exactly, and every cell in which a sampled point of the triangle lies.
std::vector<std::array<glm::vec3, 3>> thin_prism(float length, float radius, const glm::vec3& origin,
                                                 const glm::vec3& axis, const glm::vec3& side) {
  glm::dvec3 a = glm::normalize(glm::dvec3(axis)), s = glm::normalize(glm::dvec3(side));
  glm::dvec3 t = glm::cross(a, s);
  s = glm::cross(t, a);
  glm::vec3 ring[2][6], cap[2];
  for (int e = 0; e < 2; ++e) {
    cap[e] = glm::vec3(glm::dvec3(origin) + double(e * length) * a);
    for (int k = 0; k < 6; ++k) {
      double phi = k * 3.14159265358979323846 / 3;
      ring[e][k] = glm::vec3(glm::dvec3(cap[e]) + double(radius) * (std::cos(phi) * s + std::sin(phi) * t));
    }
  }
  std::vector<std::array<glm::vec3, 3>> tris;
  for (int k = 0; k < 6; ++k) {
    int k1 = (k + 1) % 6;
    tris.push_back({ring[0][k], ring[1][k], ring[1][k1]});
    tris.push_back({ring[0][k], ring[1][k1], ring[0][k1]});
    tris.push_back({cap[0], ring[0][k1], ring[0][k]});
    tris.push_back({cap[1], ring[1][k], ring[1][k1]});
  }
  return tris;
}

TEST(Bounds, ThinPrismInAGridOfCells) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  int cells_met = 0, points = 0;
  for (float scale : {1e-3f, 1e-1f, 1.f, 1e2f, 1e4f})
    for (int far = 0; far < 2; ++far)
      for (float across : {0.02f, 2e-4f})
        for (int tilted = 0; tilted < 2; ++tilted) {
          glm::vec3 axis = tilted ? glm::vec3(1.f, 0.013f, -0.007f) : glm::vec3(1.f, 0.f, 0.f);
          glm::vec3 origin = far ? 1e4f * scale * glm::vec3(0.3f, 1.f, -0.6f) : glm::vec3(0.f);
          auto tris = thin_prism(20.f * scale, 0.5f * across * scale, origin, axis, glm::vec3(0.f, 1.f, 0.3f));
          Bounds3 all;
          for (auto& t : tris)
            for (auto& p : t) all.extend(p);
          const int n[3] = {10, 3, 3};
          glm::vec3 size = all.extent() / glm::vec3(n[0], n[1], n[2]);
          auto cell_box = [&](int x, int y, int z) {
            int k[3] = {x, y, z};
            glm::vec3 lo, hi;
            for (int a = 0; a < 3; ++a) {
              lo[a] = all.lo[a] + float(k[a]) * size[a];
              hi[a] = k[a] == n[a] - 1 ? all.hi[a] : all.lo[a] + float(k[a] + 1) * size[a];
            }
            return Bounds3(lo, hi);
          };
          for (const auto& t : tris) {
            for (int x = 0; x < n[0]; ++x)
              for (int y = 0; y < n[1]; ++y)
                for (int z = 0; z < n[2]; ++z) {
                  Bounds3 cell = cell_box(x, y, z);
                  if (!test::exact_triangle_overlaps_box(t[0], t[1], t[2], cell)) continue;
                  ++cells_met;
                  ASSERT_TRUE(triangle_overlaps_box(t[0], t[1], t[2], cell)) << scale << " " << x << y << z;
                  std::vector<test::QVec> exact = test::exact_clip(t[0], t[1], t[2], cell);
                  test::QVec lo, hi;
                  Bounds3 r = clip_triangle_bounds(t[0], t[1], t[2], cell);
                  if (!test::exact_bounds(exact, &lo, &hi)) continue;  // touching by a degenerate edge only
                  ASSERT_FALSE(r.empty());
                  for (int a = 0; a < 3; ++a) {
                    ASSERT_LE(test::Q(double(r.lo[a])), lo[a]) << scale << " " << far << " " << tilted;
                    ASSERT_GE(test::Q(double(r.hi[a])), hi[a]) << scale << " " << far << " " << tilted;
                  }
                }
            // Sampled points: the cells they lie in (exactly) accept the triangle.
            for (int s = 0; s < 40; ++s) {
              double b1 = w(rng), b2 = w(rng);
              if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
              test::QVec q;
              for (int a = 0; a < 3; ++a)
                q[a] = (1 - test::Q(b1) - test::Q(b2)) * double(t[0][a]) + test::Q(b1) * double(t[1][a]) +
                       test::Q(b2) * double(t[2][a]);
              int k[3];
              for (int a = 0; a < 3; ++a)
                k[a] = size[a] > 0.f ? std::clamp(int((q[a].get_d() - all.lo[a]) / size[a]), 0, n[a] - 1) : 0;
              for (int dx = -1; dx <= 1; ++dx)  // the neighbours too: the point may sit on a shared face
                for (int dy = -1; dy <= 1; ++dy)
                  for (int dz = -1; dz <= 1; ++dz) {
                    int c[3] = {k[0] + dx, k[1] + dy, k[2] + dz};
                    if (c[0] < 0 || c[1] < 0 || c[2] < 0 || c[0] >= n[0] || c[1] >= n[1] || c[2] >= n[2]) continue;
                    Bounds3 cell = cell_box(c[0], c[1], c[2]);
                    bool inside = true;
                    for (int a = 0; a < 3; ++a) inside = inside && q[a] >= double(cell.lo[a]) && q[a] <= double(cell.hi[a]);
                    if (!inside) continue;
                    ++points;
                    ASSERT_TRUE(triangle_overlaps_box(t[0], t[1], t[2], cell));
                    Bounds3 r = clip_triangle_bounds(t[0], t[1], t[2], cell);
                    for (int a = 0; a < 3; ++a) {
                      ASSERT_LE(test::Q(double(r.lo[a])), q[a]);
                      ASSERT_GE(test::Q(double(r.hi[a])), q[a]);
                    }
                  }
            }
          }
        }
  EXPECT_GT(cells_met, 5000);
  EXPECT_GT(points, 30000);
}

}  // namespace
}  // namespace raystep
