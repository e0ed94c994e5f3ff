// tri_box_overlap.h: the grid inserts a triangle into every cell it overlaps, so the test must never reject a
// triangle that touches the box. Checked against exact rational SAT (exact_reference.h) on slivers, needles,
// triangles in a face plane, touching at a corner or an edge, and huge triangles through small boxes, at scales
// 1e-3 .. 1e4, at the origin and 1e4 sizes away from it; plus analytic cases and the sphere-box test.
#include <gtest/gtest.h>

#include <random>

#include "exact_reference.h"
#include "raystep/geometry/tri_box_overlap.h"

namespace raystep {
namespace {

TEST(TriBoxOverlap, AnalyticCases) {
  const Bounds3 box(glm::vec3(0.f), glm::vec3(1.f));
  // Inside, crossing, missing beside the box, missing across a corner (only the plane or an edge axis separates).
  EXPECT_TRUE(triangle_overlaps_box({0.2f, 0.2f, 0.5f}, {0.8f, 0.2f, 0.5f}, {0.5f, 0.8f, 0.5f}, box));
  EXPECT_TRUE(triangle_overlaps_box({-5.f, -5.f, 0.5f}, {5.f, -5.f, 0.5f}, {0.f, 5.f, 0.5f}, box));
  EXPECT_FALSE(triangle_overlaps_box({2.f, 0.f, 0.f}, {3.f, 0.f, 0.f}, {2.f, 1.f, 0.f}, box));
  EXPECT_TRUE(triangle_overlaps_box({2.f, 0.f, 0.f}, {0.f, 2.f, 0.f}, {0.f, 0.f, 2.f}, box));  // x+y+z = 2
  EXPECT_FALSE(triangle_overlaps_box({4.f, 0.f, 0.f}, {0.f, 4.f, 0.f}, {0.f, 0.f, 4.f}, box));  // x+y+z = 4
  // Touching only: a vertex at a corner, an edge along a box edge, lying in a face.
  EXPECT_TRUE(triangle_overlaps_box({1.f, 1.f, 1.f}, {2.f, 1.f, 1.f}, {2.f, 2.f, 2.f}, box));
  EXPECT_TRUE(triangle_overlaps_box({-1.f, 0.f, 0.f}, {2.f, 0.f, 0.f}, {0.f, -1.f, -1.f}, box));
  EXPECT_TRUE(triangle_overlaps_box({0.f, 0.f, 1.f}, {3.f, 0.f, 1.f}, {0.f, 3.f, 1.f}, box));
  // The plane x + y = 2 touches the box along the edge x = y = 1 only; x + y = 2.5 misses.
  EXPECT_TRUE(triangle_overlaps_box({2.f, 0.f, -1.f}, {0.f, 2.f, -1.f}, {1.f, 1.f, 5.f}, box));
  EXPECT_FALSE(triangle_overlaps_box({2.5f, 0.f, -1.f}, {0.f, 2.5f, -1.f}, {1.25f, 1.25f, 5.f}, box));
  // Degenerate triangles: a segment through the box, a segment beside it, a point on a face.
  EXPECT_TRUE(triangle_overlaps_box({-1.f, 0.5f, 0.5f}, {2.f, 0.5f, 0.5f}, {-1.f, 0.5f, 0.5f}, box));
  EXPECT_FALSE(triangle_overlaps_box({-1.f, 1.5f, 0.5f}, {0.5f, 3.f, 0.5f}, {-1.f, 1.5f, 0.5f}, box));
  EXPECT_TRUE(triangle_overlaps_box({1.f, 0.5f, 0.5f}, {1.f, 0.5f, 0.5f}, {1.f, 0.5f, 0.5f}, box));
}

// Random thin triangles touching or nearly touching random boxes (some boxes are needles or slabs too).
struct Case {
  glm::vec3 p[3];
  Bounds3 box;
};

Case make_case(std::mt19937& rng, int kind, float scale, const glm::vec3& offset) {
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  auto rnd = [&] { return glm::vec3(u(rng), u(rng), u(rng)); };
  Case c;
  glm::vec3 center = offset + scale * rnd();
  glm::vec3 half = scale * (0.05f + glm::vec3(w(rng), w(rng), w(rng)));
  if (rng() % 4 == 0) half[rng() % 3] *= 1e-5f;  // a slab-shaped (or, twice, needle-shaped) box
  if (rng() % 4 == 0) half[rng() % 3] *= 1e-5f;
  c.box = Bounds3(center - half, center + half);
  const Bounds3& b = c.box;
  glm::vec3 corner(rng() % 2 ? b.lo.x : b.hi.x, rng() % 2 ? b.lo.y : b.hi.y, rng() % 2 ? b.lo.z : b.hi.z);
  float tiny = scale * std::pow(10.f, -float(3 + rng() % 5));  // 1e-3 .. 1e-7 of the scale
  switch (kind) {
    case 0:  // general, around the box
      for (auto& p : c.p) p = center + 2.f * scale * rnd();
      break;
    case 1:  // sliver: the third vertex within `tiny` of the opposite edge
      c.p[0] = center + 2.f * scale * rnd();
      c.p[1] = center + 2.f * scale * rnd();
      c.p[2] = c.p[0] + w(rng) * (c.p[1] - c.p[0]) + tiny * rnd();
      break;
    case 2:  // needle: two vertices within `tiny` of each other
      c.p[0] = center + 2.f * scale * rnd();
      c.p[1] = c.p[0] + tiny * rnd();
      c.p[2] = center + 2.f * scale * rnd();
      break;
    case 3: {  // lying in the plane of a box face, or just beside it
      int a = int(rng() % 3);
      float plane = rng() % 2 ? b.lo[a] : b.hi[a];
      for (auto& p : c.p) {
        p = center + 2.f * scale * rnd();
        p[a] = plane;
      }
      if (rng() % 2) c.p[rng() % 3][a] = plane + tiny * u(rng);  // slightly tilted
      break;
    }
    case 4: {  // a sliver whose long edge runs through (a rounding of) a box corner
      glm::vec3 dir = rnd();
      c.p[0] = corner + scale * dir;
      c.p[1] = corner - scale * w(rng) * dir;
      c.p[2] = c.p[1] + tiny * rnd();
      break;
    }
    case 5: {  // a vertex on a box edge or corner, the rest outside
      c.p[0] = corner;
      if (rng() % 2) c.p[0][rng() % 3] = center[rng() % 3];
      c.p[1] = c.p[0] + scale * (corner - center + 0.5f * half * rnd());
      c.p[2] = c.p[0] + scale * (corner - center + 0.5f * half * rnd());
      break;
    }
    default: {  // a huge sliver passing through a small box: 1e3 .. 1e10 times the box's size, one end near it
      glm::vec3 dir = rnd();
      glm::vec3 through = center + half * rnd();
      float length = scale * std::pow(10.f, float(3 + rng() % 8)) * 1e-5f;
      c.box = Bounds3(center - 1e-5f * half, center + 1e-5f * half);
      through = center + 1e-5f * half * rnd();
      c.p[0] = through + length * dir;
      c.p[1] = through - (rng() % 2 ? length : 1e-5f * scale) * w(rng) * dir;
      c.p[2] = c.p[0] + length * std::pow(10.f, -float(4 + rng() % 4)) * rnd();
      break;
    }
  }
  return c;
}

// A triangle that meets the box exactly is never rejected; and the test still rejects most that do not.
TEST(TriBoxOverlap, NeverRejectsATouchingTriangle) {
  std::mt19937 rng(11);
  int touching = 0, rejected = 0, separate = 0, separate_rejected = 0;
  int touching_by_kind[7] = {};
  for (int i = 0; i < 70000; ++i) {
    const float scale = std::pow(10.f, float(int(rng() % 8) - 3));  // 1e-3 .. 1e4
    const glm::vec3 offset = (i % 2) ? 1e4f * scale * glm::vec3(0.8f, -0.6f, 0.3f) : glm::vec3(0.f);
    const int kind = i % 7;
    Case c = make_case(rng, kind, scale, offset);
    bool exact = test::exact_triangle_overlaps_box(c.p[0], c.p[1], c.p[2], c.box);
    bool got = triangle_overlaps_box(c.p[0], c.p[1], c.p[2], c.box);
    if (exact) {
      ++touching;
      ++touching_by_kind[kind];
      if (!got) {
        ++rejected;
        ADD_FAILURE() << "case " << i << " kind " << kind << " scale " << scale;
        if (rejected > 10) return;
      }
    } else {
      ++separate;
      separate_rejected += !got;
    }
  }
  EXPECT_EQ(rejected, 0);
  for (int k = 0; k < 7; ++k) EXPECT_GT(touching_by_kind[k], 1000) << "kind " << k;
  EXPECT_GT(separate, 10000);
  // Conservative, not trivially true (the relative margin of 2^-20 of the box's position accepts some near misses
  // far from the origin).
  EXPECT_GT(separate_rejected, separate * 8 / 10) << separate_rejected << " of " << separate;
}

// Points of a triangle (vertices, points on edges, barycentric samples) that lie in a box imply overlap, for the
// boxes of a grid of cells around slivers and needles.
TEST(TriBoxOverlap, SampledPointsInACellImplyOverlap) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    const float scale = std::pow(10.f, float(int(rng() % 8) - 3));
    const glm::vec3 offset = (i % 2) ? 1e4f * scale * glm::vec3(-0.3f, 0.9f, 0.5f) : glm::vec3(0.f);
    Case c = make_case(rng, 1 + i % 2, scale, offset);  // slivers and needles
    Bounds3 tb(c.p[0], c.p[1]);
    tb.extend(c.p[2]);
    const int n = 8;
    glm::vec3 cell = (tb.hi - tb.lo) / float(n);
    for (int s = 0; s < 64; ++s) {
      double b1 = w(rng), b2 = w(rng);
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      if (s < 3) b1 = s == 1, b2 = s == 2;      // the vertices
      if (s >= 3 && s < 6) b2 = 0;              // on an edge
      // The point with these (double) barycentrics, exactly: a rounded one may lie just off the triangle.
      test::QVec x;
      for (int a = 0; a < 3; ++a)
        x[a] = (1 - test::Q(b1) - test::Q(b2)) * double(c.p[0][a]) + test::Q(b1) * double(c.p[1][a]) +
               test::Q(b2) * double(c.p[2][a]);
      glm::vec3 lo, hi;
      for (int a = 0; a < 3; ++a) {
        int k = cell[a] > 0.f ? std::min(n - 1, int((x[a].get_d() - tb.lo[a]) / cell[a])) : 0;
        lo[a] = cell[a] > 0.f ? tb.lo[a] + float(k) * cell[a] : tb.lo[a];
        hi[a] = cell[a] > 0.f ? (k == n - 1 ? tb.hi[a] : tb.lo[a] + float(k + 1) * cell[a]) : tb.hi[a];
      }
      Bounds3 box(lo, hi);
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && x[a] >= double(box.lo[a]) && x[a] <= double(box.hi[a]);
      if (!inside) continue;  // the cell's float corners rounded away from the point
      ++checked;
      ASSERT_TRUE(triangle_overlaps_box(c.p[0], c.p[1], c.p[2], box)) << i << " " << s;
    }
  }
  EXPECT_GT(checked, 150000);
}

TEST(TriBoxOverlap, SphereBox) {
  const Bounds3 box(glm::vec3(0.f), glm::vec3(1.f));
  EXPECT_TRUE(sphere_overlaps_box({0.5f, 0.5f, 0.5f}, 0.1f, box));
  EXPECT_TRUE(sphere_overlaps_box({2.f, 0.5f, 0.5f}, 1.f, box));  // touching a face
  EXPECT_FALSE(sphere_overlaps_box({2.f, 2.f, 2.f}, 1.7f, box));  // sqrt(3) = 1.732 from the corner
  EXPECT_TRUE(sphere_overlaps_box({2.f, 2.f, 2.f}, 1.74f, box));
}

}  // namespace
}  // namespace raystep
