// The bounds of the part of a triangle inside an axis-aligned box, by Sutherland-Hodgman polygon clipping
// ("Reentrant polygon clipping", 1974) against the box's six planes: the kd-tree's "perfect splits" (Havran
// 2000; Wald and Havran 2006). Computed in double, with a rounding error bound from gamma_double(n), and rounded
// outward to float, so the result contains the exact clipped triangle: a structure built on these bounds never
// loses a primitive to rounding.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/numerics.h"

namespace raystep {

inline Bounds3 intersection_of(const Bounds3& a, const Bounds3& b) {
  Bounds3 r;
  r.lo = glm::max(a.lo, b.lo);
  r.hi = glm::min(a.hi, b.hi);
  return r;
}

// Error-free transformations: the exact rounding error of a double sum (Knuth's TwoSum) and of a double
// product (Dekker's TwoProduct with Veltkamp's split). They tell when an interpolated coordinate came out exact.
inline double two_sum_error(double a, double b, double sum) {
  double bb = sum - a;
  return (a - (sum - bb)) + (b - bb);
}
inline double two_product_error(double a, double b, double product) {
  const double split = 134217729.0;  // 2^27 + 1
  double ca = split * a, cb = split * b;
  double a_hi = ca - (ca - a), a_lo = a - a_hi;
  double b_hi = cb - (cb - b), b_lo = b - b_hi;
  return ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
}

namespace triangle_clip_detail {

struct Vertex {
  glm::dvec3 p;
  uint32_t exact;  // bit a: coordinate a is an exact float
};

// The bound on how far the computed polygon's coordinates on each axis may be from the exact ones: one crossing
// rounds a coordinate by at most gamma(14) of the largest magnitude m (t within gamma(3); s_b + t (e_b - s_b)
// within gamma(5) |e_b - s_b| + gamma(1) (|s_b| + |e_b - s_b|), |e_b - s_b| <= 2 m), a coordinate goes through at
// most six crossings, and the outward subtraction rounds once more: gamma(96) m.
inline glm::dvec3 rounding_bound(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  glm::dvec3 magnitude =
      glm::max(glm::abs(glm::dvec3(p0)), glm::max(glm::abs(glm::dvec3(p1)), glm::abs(glm::dvec3(p2))));
  return gamma_double(96) * magnitude;
}

// One Sutherland-Hodgman step: poly[0, n) by the half-space x_a >= plane (keep_above) or x_a <= plane, into
// next; returns the new vertex count. While every vertex's coordinate a is exact, sides and crossings follow the
// exact polygon's, each vertex within the bound of its own. Once one is rounded, a crossing computed from it can
// slide far along an edge nearly parallel to the plane (by the rounding over the edge's slope: 1e-5 of a unit
// on a 20-long edge at 1e4), so the step clips by the plane moved outward by the bound (`shift`, at least the
// rounding of any coordinate), which keeps every point within the bound of the exact polygon in the result,
// and the bound then holds for the whole polygon: its coordinates are marked inexact wherever one is.
inline int clip_polygon(Vertex* poly, int n, int a, bool keep_above, double plane, double shift, Vertex* next) {
  uint32_t all_exact = 7u;
  for (int i = 0; i < n; ++i) all_exact &= poly[i].exact;
  if (!(all_exact >> a & 1u)) {
    plane = keep_above ? plane - shift : plane + shift;
    for (int i = 0; i < n; ++i) poly[i].exact = all_exact;
  }
  auto inside = [&](const Vertex& v) { return keep_above ? v.p[a] >= plane : v.p[a] <= plane; };
  int m = 0;
  bool s_in = inside(poly[n - 1]);
  for (int i = 0, j = n - 1; i < n; j = i++) {  // the edge from s = poly[j] to e = poly[i]
    const Vertex& s = poly[j];
    const Vertex& e = poly[i];
    const bool e_in = inside(e);
    if (s_in != e_in) {
      double t = (plane - s.p[a]) / (e.p[a] - s.p[a]);
      t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
      Vertex& x = next[m++];
      x.p = s.p + t * (e.p - s.p);
      x.p[a] = plane;
      x.exact = all_exact & (1u << a);  // the plane itself, unless moved
      double num = plane - s.p[a], den = e.p[a] - s.p[a];
      bool t_exact = ((s.exact & e.exact) >> a & 1u) && t > 0.0 && t < 1.0 && t * den == num &&
                     two_product_error(t, den, t * den) == 0.0 && two_sum_error(plane, -s.p[a], num) == 0.0 &&
                     two_sum_error(e.p[a], -s.p[a], den) == 0.0;
      for (int b = 0; b < 3; ++b) {
        if (b == a || !(s.exact & e.exact & (1u << b))) continue;
        double d = e.p[b] - s.p[b], r = t * d;
        if (d == 0.0 || (t_exact && two_sum_error(e.p[b], -s.p[b], d) == 0.0 &&
                         two_product_error(t, d, r) == 0.0 && two_sum_error(s.p[b], r, x.p[b]) == 0.0))
          x.exact |= 1u << b;
      }
    }
    if (e_in) next[m++] = e;
    s_in = e_in;
  }
  return m;
}

// A polygon being clipped in two buffers used in turn.
struct Polygon {
  Vertex buffer[2][10];
  int current = 0, n = 0;

  const Vertex* vertices() const { return buffer[current]; }
  // Clips by the planes of box on the axes [from, to) that the triangle (bounds tri) crosses, x before y before
  // z, lower plane first; widen is rounding_bound(); false when nothing is left.
  bool clip_by(const Bounds3& tri, const Bounds3& box, int from, int to, const glm::dvec3& widen) {
    for (int a = from; a < to; ++a)
      for (int side = 0; side < 2; ++side) {
        const bool keep_above = side == 0;
        if (keep_above ? tri.lo[a] >= box.lo[a] : tri.hi[a] <= box.hi[a]) continue;
        n = clip_polygon(buffer[current], n, a, keep_above, keep_above ? box.lo[a] : box.hi[a], widen[a],
                         buffer[1 - current]);
        current = 1 - current;
        if (n == 0) return false;
      }
    return true;
  }
  void copy_to(Polygon* other) const {
    other->current = 0;
    other->n = n;
    std::copy(buffer[current], buffer[current] + n, other->buffer[0]);
  }
  // The polygon's bounds, inexact coordinates widened by the rounding bound, rounded outward, within limit.
  Bounds3 bounds(const glm::dvec3& widen, const Bounds3& limit) const {
    const Vertex* poly = vertices();
    glm::dvec3 lo(kInfinity), hi(-kInfinity);
    for (int i = 0; i < n; ++i)
      for (int b = 0; b < 3; ++b) {
        double w = (poly[i].exact >> b) & 1u ? 0.0 : widen[b];
        double l = poly[i].p[b] - w, h = poly[i].p[b] + w;
        lo[b] = l < lo[b] ? l : lo[b];
        hi[b] = h > hi[b] ? h : hi[b];
      }
    Bounds3 r;
    for (int b = 0; b < 3; ++b) {
      float l = float(lo[b]), h = float(hi[b]);
      if (double(l) > lo[b]) l = next_float_down(l);
      if (double(h) < hi[b]) h = next_float_up(h);
      r.lo[b] = l;
      r.hi[b] = h;
    }
    return intersection_of(r, limit);
  }

  void start(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
    current = 0;
    n = 3;
    buffer[0][0] = {glm::dvec3(p0), 7u};
    buffer[0][1] = {glm::dvec3(p1), 7u};
    buffer[0][2] = {glm::dvec3(p2), 7u};
  }
};

}  // namespace triangle_clip_detail

// Bounds of triangle (p0, p1, p2) intersected with box. Conservative: they contain every point of the exact
// intersection, and they lie within the triangle's own bounds intersected with the box. Empty when the triangle
// misses the box. Coordinates that are inputs (a vertex inside the box, a box plane) come out exactly, and so do
// interpolated ones whose arithmetic was exact (checked by error-free transformations: the common case of
// axis-aligned geometry on a lattice); other interpolated ones are widened by the rounding bound (gamma_double(96)
// of the coordinates' magnitude) and rounded outward, one float ulp at most.
inline Bounds3 clip_triangle_bounds(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                    const Bounds3& box) {
  Bounds3 tri(p0, p1);
  tri.extend(p2);
  const Bounds3 limit = intersection_of(tri, box);
  if (limit.empty()) return Bounds3();
  triangle_clip_detail::Polygon poly;
  poly.start(p0, p1, p2);
  const glm::dvec3 widen = triangle_clip_detail::rounding_bound(p0, p1, p2);
  // Sutherland-Hodgman: clip the polygon by one half-space at a time; only planes the triangle crosses.
  if (!poly.clip_by(tri, box, 0, 3, widen)) return Bounds3();
  return poly.bounds(widen, limit);
}

// The faster variant for the kd-tree's split step: the bounds of a triangle in both children of `box` cut at
// `position` on `axis`, bit for bit clip_triangle_bounds(p0, p1, p2, below) and clip_triangle_bounds(p0, p1, p2,
// above) (tests/core/triangle_clip_test.cpp checks it). The two clips run the same operations on the same
// numbers up to the cut axis, whose planes come after those of the axes before it: that part is clipped once,
// then the polygon is copied and clipped on by each child's remaining planes.
inline void clip_triangle_bounds_split(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                       const Bounds3& box, int axis, float position, Bounds3* below,
                                       Bounds3* above) {
  using triangle_clip_detail::Polygon;
  Bounds3 below_box = box, above_box = box;
  below_box.hi[axis] = position;
  above_box.lo[axis] = position;
  *below = Bounds3();
  *above = Bounds3();
  Bounds3 tri(p0, p1);
  tri.extend(p2);
  const Bounds3 below_limit = intersection_of(tri, below_box), above_limit = intersection_of(tri, above_box);
  const bool want_below = !below_limit.empty(), want_above = !above_limit.empty();
  if (!want_below && !want_above) return;

  // The planes both clips share: those of the axes before the cut.
  Polygon poly;
  poly.start(p0, p1, p2);
  const glm::dvec3 widen = triangle_clip_detail::rounding_bound(p0, p1, p2);
  if (!poly.clip_by(tri, box, 0, axis, widen)) return;
  // Then each child on its own: the cut axis and the axes after it.
  if (want_above) {
    Polygon upper;
    poly.copy_to(&upper);
    if (upper.clip_by(tri, above_box, axis, 3, widen)) *above = upper.bounds(widen, above_limit);
  }
  if (want_below && poly.clip_by(tri, below_box, axis, 3, widen)) *below = poly.bounds(widen, below_limit);
}

}  // namespace raystep
