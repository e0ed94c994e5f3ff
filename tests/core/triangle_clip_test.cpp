// triangle_clip.h: the bounds of a triangle clipped to a box are exact where the arithmetic is, conservative
// everywhere (every point of the triangle inside the box is inside them), and never larger than the
// triangle's bounds intersected with the box.
#include <gtest/gtest.h>

#include <random>

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

}  // namespace
}  // namespace raystep
