// triangle_clip.h: the bounds of a triangle clipped to a box are exact where the arithmetic is, conservative
// everywhere (every point of the triangle inside the box is inside them), and never larger than the
// triangle's bounds intersected with the box.
#include <gtest/gtest.h>

#include <random>

#include "exact_reference.h"
#include "raystep/geometry/triangle_clip.h"

namespace raystep {
namespace {

TEST(TriangleClip, InsideMissingAndExactCuts) {
  Bounds3 box(glm::vec3(0.f), glm::vec3(4.f));
  glm::vec3 a(1, 1, 1), b(2, 1, 1), c(1, 3, 2);
  Bounds3 r = clip_triangle_bounds(a, b, c, box);
  EXPECT_EQ(r.lo, glm::vec3(1, 1, 1));
  EXPECT_EQ(r.hi, glm::vec3(2, 3, 2));
  EXPECT_TRUE(clip_triangle_bounds(a + 10.f, b + 10.f, c + 10.f, box).empty());
  // The triangle x + y <= 4 in z = 0, clipped to x >= 3.5: y in [0, 0.5], exactly.
  Bounds3 cut(glm::vec3(3.5f, 0.f, 0.f), glm::vec3(4.f, 4.f, 0.f));
  Bounds3 q = clip_triangle_bounds(glm::vec3(0, 0, 0), glm::vec3(4, 0, 0), glm::vec3(0, 4, 0), cut);
  EXPECT_EQ(q.lo, glm::vec3(3.5f, 0.f, 0.f));
  EXPECT_EQ(q.hi, glm::vec3(4.f, 0.5f, 0.f));
  // Touching the box in one point (a vertex on a face) is not missing it.
  Bounds3 t = clip_triangle_bounds(glm::vec3(4, 1, 1), glm::vec3(5, 1, 1), glm::vec3(5, 2, 1), box);
  EXPECT_FALSE(t.empty());
  EXPECT_EQ(t.lo.x, 4.f);
  EXPECT_EQ(t.hi.x, 4.f);
}

TEST(TriangleClip, ConservativeOnRandomTriangles) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-2.f, 2.f), w(0.f, 1.f);
  int clipped = 0;
  for (int k = 0; k < 2000; ++k) {
    glm::vec3 p[3] = {{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    Bounds3 box(glm::vec3(u(rng), u(rng), u(rng)), glm::vec3(u(rng), u(rng), u(rng)));
    Bounds3 r = clip_triangle_bounds(p[0], p[1], p[2], box);
    Bounds3 limit(p[0], p[1]);
    limit.extend(p[2]);
    limit = intersection_of(limit, box);
    if (!r.empty()) {
      ++clipped;
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(r.lo[a], limit.lo[a]);
        EXPECT_LE(r.hi[a], limit.hi[a]);
      }
    }
    // Points of the triangle inside the box lie inside the clipped bounds.
    for (int s = 0; s < 200; ++s) {
      float b1 = w(rng), b2 = w(rng);
      if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
      glm::dvec3 x = (1.0 - b1 - b2) * glm::dvec3(p[0]) + double(b1) * glm::dvec3(p[1]) + double(b2) * glm::dvec3(p[2]);
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside &= x[a] >= box.lo[a] && x[a] <= box.hi[a];
      if (!inside) continue;
      ASSERT_FALSE(r.empty());
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(double(r.lo[a]), x[a]);
        EXPECT_GE(double(r.hi[a]), x[a]);
      }
    }
  }
  EXPECT_GT(clipped, 100);
}

// The kd-tree's split step clips a triangle to both children at once: bit for bit the two plain clips, on random
// triangles and boxes (many planes crossed), on a lattice (exact arithmetic), for vertices on the cut plane and
// for cuts at the triangle's own bounds.
TEST(TriangleClip, SplitGivesTheTwoPlainClipsBitForBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-2.f, 2.f), f(0.f, 1.f);
  std::uniform_int_distribution<int> lattice(-8, 8), pick(0, 4);
  auto same_bits = [](const Bounds3& a, const Bounds3& b) {
    for (int k = 0; k < 3; ++k)
      if (float_to_bits(a.lo[k]) != float_to_bits(b.lo[k]) || float_to_bits(a.hi[k]) != float_to_bits(b.hi[k]))
        return false;
    return true;
  };
  int both = 0, one = 0;
  for (int k = 0; k < 200000; ++k) {
    glm::vec3 p[3];
    Bounds3 box;
    const int kind = k % 4;
    if (kind == 3) {  // a lattice of halves: interpolation is often exact
      for (auto& v : p) v = 0.5f * glm::vec3(lattice(rng), lattice(rng), lattice(rng));
      box = Bounds3(0.5f * glm::vec3(lattice(rng), lattice(rng), lattice(rng)),
                    0.5f * glm::vec3(lattice(rng), lattice(rng), lattice(rng)));
    } else {
      for (auto& v : p) v = glm::vec3(u(rng), u(rng), u(rng));
      // Boxes from large to tiny, so that a triangle crosses from one to six of their planes.
      glm::vec3 c(u(rng), u(rng), u(rng)), h = glm::vec3(f(rng), f(rng), f(rng)) * (kind == 0 ? 2.f : kind == 1 ? 0.5f : 0.05f);
      box = Bounds3(c - h, c + h);
    }
    const int axis = k % 3;
    if (!(box.lo[axis] < box.hi[axis])) continue;
    float position;
    switch (pick(rng)) {
      case 0: position = p[k % 3][axis]; break;  // through a vertex
      default: position = box.lo[axis] + f(rng) * (box.hi[axis] - box.lo[axis]); break;
    }
    if (!(box.lo[axis] < position && position < box.hi[axis])) continue;
    Bounds3 below_box = box, above_box = box;
    below_box.hi[axis] = position;
    above_box.lo[axis] = position;
    Bounds3 below, above;
    clip_triangle_bounds_split(p[0], p[1], p[2], box, axis, position, &below, &above);
    const Bounds3 plain_below = clip_triangle_bounds(p[0], p[1], p[2], below_box);
    const Bounds3 plain_above = clip_triangle_bounds(p[0], p[1], p[2], above_box);
    ASSERT_EQ(below.empty(), plain_below.empty()) << k;
    ASSERT_EQ(above.empty(), plain_above.empty()) << k;
    if (!below.empty()) ASSERT_TRUE(same_bits(below, plain_below)) << k;
    if (!above.empty()) ASSERT_TRUE(same_bits(above, plain_above)) << k;
    if (!below.empty() && !above.empty()) ++both;
    else if (!below.empty() || !above.empty()) ++one;
  }
  EXPECT_GT(both, 10000);
  EXPECT_GT(one, 10000);
}

// Slivers, needles and nearly axis-aligned triangles (edges at slopes of 1e-3 .. 1e-8 to a box face: where a
// rounded crossing point, clipped again, slides far along the edge) against boxes, some of them thin, at scales
// 1e-3 .. 1e4, at the origin and 1e4 sizes away: the clipped bounds contain the exact clipped triangle
// (rationals, exact_reference.h), are empty only when it is, and both children of a split contain theirs.
struct ClipCase {
  glm::vec3 p[3];
  Bounds3 box;
};

ClipCase make_clip_case(std::mt19937& rng, int kind, float scale, const glm::vec3& offset) {
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  auto rnd = [&] { return glm::vec3(u(rng), u(rng), u(rng)); };
  ClipCase c;
  glm::vec3 center = offset + scale * rnd();
  glm::vec3 half = scale * (0.05f + glm::vec3(w(rng), w(rng), w(rng)));
  if (rng() % 4 == 0) half[rng() % 3] *= 1e-5f;
  c.box = Bounds3(center - half, center + half);
  float tiny = scale * std::pow(10.f, -float(3 + rng() % 6));  // 1e-3 .. 1e-8 of the scale
  switch (kind) {
    case 0:  // sliver
      c.p[0] = center + 1.2f * scale * rnd();
      c.p[1] = center + 1.2f * scale * rnd();
      c.p[2] = c.p[0] + w(rng) * (c.p[1] - c.p[0]) + tiny * rnd();
      break;
    case 1:  // needle
      c.p[0] = center + 1.2f * scale * rnd();
      c.p[1] = c.p[0] + tiny * rnd();
      c.p[2] = center + 1.2f * scale * rnd();
      break;
    case 3: {  // long and thin along one axis (20 : 0.02 and thinner), crossed by a box cutting it across
      int a = int(rng() % 3), b = (a + 1) % 3, e = (a + 2) % 3;
      glm::vec3 base = center;
      base[a] -= 10.f * scale;
      c.p[0] = c.p[1] = c.p[2] = base;
      c.p[1][a] += 20.f * scale, c.p[2][a] += 20.f * scale;
      c.p[0][b] += 0.01f * scale * u(rng);
      c.p[1][b] += 0.01f * scale * std::pow(10.f, -float(rng() % 8)) * u(rng);
      c.p[2][b] += 0.01f * scale * std::pow(10.f, -float(rng() % 8)) * u(rng);
      for (auto& p : c.p) p[e] += scale * u(rng);
      glm::vec3 lo = center - 5.f * scale * glm::vec3(1.f), hi = center + 5.f * scale * glm::vec3(1.f);
      lo[b] = center[b] + 0.01f * scale * u(rng);
      hi[b] = center[b] + 0.02f * scale;
      c.box = Bounds3(lo, hi);
      break;
    }
    default: {  // nearly axis-aligned: a triangle in the plane x_a = const, each vertex tilted by `tiny`,
                // with edges nearly along an axis too
      int a = int(rng() % 3), b = (a + 1 + int(rng() % 2)) % 3;
      glm::vec3 q0 = center + 1.2f * scale * rnd(), q1 = q0, q2 = q0;
      q1[b] += 3.f * scale * u(rng);
      q2[3 - a - b] += 3.f * scale * u(rng);
      c.p[0] = q0, c.p[1] = q1, c.p[2] = q2;
      for (auto& p : c.p) p += tiny * rnd();
      break;
    }
  }
  return c;
}

bool contains_exact(const Bounds3& r, const std::vector<test::QVec>& poly) {
  test::QVec lo, hi;
  if (!test::exact_bounds(poly, &lo, &hi)) return true;
  if (r.empty()) return false;
  for (int a = 0; a < 3; ++a)
    if (test::Q(double(r.lo[a])) > lo[a] || test::Q(double(r.hi[a])) < hi[a]) return false;
  return true;
}

TEST(TriangleClip, ContainsTheExactClipOfThinTriangles) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> f(0.f, 1.f);
  int met = 0, failures = 0;
  for (int i = 0; i < 40000; ++i) {
    const float scale = std::pow(10.f, float(int(rng() % 8) - 3));  // 1e-3 .. 1e4
    // At the origin, far along a diagonal, or far along one axis only (coordinates of unlike magnitudes).
    glm::vec3 offset = (i % 3 == 1) ? 1e4f * scale * glm::vec3(0.6f, 0.7f, -0.4f) : glm::vec3(0.f);
    if (i % 3 == 2) offset[rng() % 3] = 1e4f * scale;
    ClipCase c = make_clip_case(rng, int(rng() % 4), scale, offset);
    std::vector<test::QVec> exact = test::exact_clip(c.p[0], c.p[1], c.p[2], c.box);
    met += !exact.empty();
    Bounds3 r = clip_triangle_bounds(c.p[0], c.p[1], c.p[2], c.box);
    bool ok = contains_exact(r, exact);
    // The split step, at a random position, for both children.
    const int axis = i % 3;
    float position = c.box.lo[axis] + f(rng) * (c.box.hi[axis] - c.box.lo[axis]);
    Bounds3 below_box = c.box, above_box = c.box, below, above;
    below_box.hi[axis] = position;
    above_box.lo[axis] = position;
    clip_triangle_bounds_split(c.p[0], c.p[1], c.p[2], c.box, axis, position, &below, &above);
    ok = ok && contains_exact(below, test::exact_clip(c.p[0], c.p[1], c.p[2], below_box)) &&
         contains_exact(above, test::exact_clip(c.p[0], c.p[1], c.p[2], above_box));
    if (!ok) {
      ADD_FAILURE() << "case " << i << " scale " << scale;
      if (++failures > 10) return;
    }
  }
  EXPECT_GT(met, 13000) << met;
}

// A triangle 20 long and 0.02 across or thinner, lying 1 .. 1e5 of its length away along its thin axis, cut across
// by a box: the clip by the long axis's planes rounds the thin coordinate of the new vertices (at 1e4, by 1e-12),
// and the following clip by a thin-axis plane used to slide its crossing along the nearly parallel long edge by
// that rounding over the edge's slope, out of the bounds (46 of 130,000 such cases, by up to 1e-5).
TEST(TriangleClip, LongThinTriangleFarAlongItsThinAxis) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int met = 0, failures = 0;
  for (int i = 0; i < 130000; ++i) {
    const float scale = std::pow(10.f, float(int(rng() % 8) - 3));
    const float far = scale * std::pow(10.f, float(rng() % 6));
    float d1 = 0.01f * std::pow(10.f, -float(rng() % 7)) * u(rng), d2 = 0.01f * std::pow(10.f, -float(rng() % 7)) * u(rng);
    glm::vec3 p[3] = {scale * glm::vec3(-10.f + u(rng), 0.f, u(rng)), scale * glm::vec3(10.f + u(rng), 0.f, u(rng)),
                      scale * glm::vec3(10.f + u(rng), 0.f, u(rng))};
    p[0].y = far + 0.01f * scale * u(rng), p[1].y = far + scale * d1, p[2].y = far + scale * d2;
    Bounds3 box(glm::vec3(scale * (-5.f + u(rng)), far + 0.01f * scale * u(rng), -2.f * scale),
                glm::vec3(scale * (5.f + u(rng)), far + 0.02f * scale, 2.f * scale));
    if (rng() % 2) std::swap(box.lo.y, box.hi.y), box = Bounds3(box.lo, box.hi);
    // The same with the axes permuted, so that each axis is the long one, the thin one and the other in turn.
    const int shift = i % 3;
    auto permute = [&](glm::vec3 v) { return glm::vec3(v[(0 + shift) % 3], v[(1 + shift) % 3], v[(2 + shift) % 3]); };
    for (auto& q : p) q = permute(q);
    box = Bounds3(permute(box.lo), permute(box.hi));
    std::vector<test::QVec> exact = test::exact_clip(p[0], p[1], p[2], box);
    if (exact.empty()) continue;
    ++met;
    if (!contains_exact(clip_triangle_bounds(p[0], p[1], p[2], box), exact)) {
      ADD_FAILURE() << "case " << i << " scale " << scale << " far " << far;
      if (++failures > 10) return;
    }
  }
  EXPECT_GT(met, 70000);
}

// Points of a sliver or needle (vertices, points on edges, barycentric samples in double) that lie in a box lie
// in its clipped bounds.
TEST(TriangleClip, SampledPointsOfThinTrianglesInsideTheBounds) {
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  int inside_points = 0;
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::pow(10.f, float(int(rng() % 8) - 3));
    glm::vec3 offset = (i % 3 == 1) ? 1e4f * scale * glm::vec3(-0.5f, 0.2f, 0.9f) : glm::vec3(0.f);
    if (i % 3 == 2) offset[rng() % 3] = -1e4f * scale;
    ClipCase c = make_clip_case(rng, int(rng() % 4), scale, offset);
    Bounds3 r = clip_triangle_bounds(c.p[0], c.p[1], c.p[2], c.box);
    for (int s = 0; s < 50; ++s) {
      double b1 = w(rng), b2 = w(rng);
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      if (s < 3) b1 = s == 1, b2 = s == 2;
      if (s >= 3 && s < 8) b2 = 0;
      // The point with these (double) barycentrics, exactly: a rounded one may lie just off the triangle.
      test::QVec x;
      for (int a = 0; a < 3; ++a)
        x[a] = (1 - test::Q(b1) - test::Q(b2)) * double(c.p[0][a]) + test::Q(b1) * double(c.p[1][a]) +
               test::Q(b2) * double(c.p[2][a]);
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && x[a] >= double(c.box.lo[a]) && x[a] <= double(c.box.hi[a]);
      if (!inside) continue;
      ++inside_points;
      ASSERT_FALSE(r.empty()) << i;
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(double(r.lo[a]), x[a]) << i << " " << s;
        ASSERT_GE(double(r.hi[a]), x[a]) << i << " " << s;
      }
    }
  }
  EXPECT_GT(inside_points, 50000);
}

}  // namespace
}  // namespace raystep
