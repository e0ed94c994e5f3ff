// Exact rational references (GMP's mpq_class) for the tests that check a floating-point geometric kernel is
// conservative or exact: the ray-triangle test, the slab test's interval, triangle-box overlap by the
// separating axis theorem, and a triangle clipped to a box. Every float and double converts to a rational
// exactly, so these answer for the exact inputs.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/ray.h"

namespace raystep::test {

using Q = mpq_class;

struct QVec {
  Q c[3];
  Q& operator[](int a) { return c[a]; }
  const Q& operator[](int a) const { return c[a]; }
};

inline QVec to_q(const glm::vec3& v) {
  return QVec{{Q(double(v.x)), Q(double(v.y)), Q(double(v.z))}};
}
inline QVec to_q(const glm::dvec3& v) {
  return QVec{{Q(v.x), Q(v.y), Q(v.z)}};
}

inline Q dot(const QVec& a, const QVec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline QVec sub(const QVec& a, const QVec& b) {
  return QVec{{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
}
inline QVec cross(const QVec& a, const QVec& b) {
  return QVec{{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}

// Does the closed triangle (p0, p1, p2) meet the closed box? The separating axis theorem on the 13 axes of
// Akenine-Moeller's test, in exact arithmetic; it is also complete for degenerate triangles (a segment or a
// point: the box normals and the segment's cross products with the box axes are among the 13), and a zero
// axis separates nothing.
inline bool exact_triangle_overlaps_box(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                        const Bounds3& box) {
  QVec v[3] = {to_q(p0), to_q(p1), to_q(p2)};
  QVec lo = to_q(box.lo), hi = to_q(box.hi);
  auto separated = [&](const QVec& w) {
    Q tmin = dot(w, v[0]), tmax = tmin;
    for (int i = 1; i < 3; ++i) {
      Q d = dot(w, v[i]);
      if (d < tmin) tmin = d;
      if (d > tmax) tmax = d;
    }
    Q bmin = 0, bmax = 0;
    for (int a = 0; a < 3; ++a) {
      Q x = w[a] * lo[a], y = w[a] * hi[a];
      bmin += x < y ? x : y;
      bmax += x < y ? y : x;
    }
    return tmin > bmax || tmax < bmin;
  };
  QVec e[3] = {sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])};
  for (int a = 0; a < 3; ++a) {
    QVec u{{0, 0, 0}};
    u[a] = 1;
    if (separated(u)) return false;
    for (int i = 0; i < 3; ++i)
      if (separated(cross(u, e[i]))) return false;
  }
  return !separated(cross(e[0], e[1]));
}

// The exact polygon triangle ∩ box (Sutherland-Hodgman in rationals); empty when they do not meet.
inline std::vector<QVec> exact_clip(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                    const Bounds3& box) {
  std::vector<QVec> poly = {to_q(p0), to_q(p1), to_q(p2)}, next;
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const Q plane = Q(double(side == 0 ? box.lo[a] : box.hi[a]));
      auto inside = [&](const QVec& v) { return side == 0 ? v[a] >= plane : v[a] <= plane; };
      next.clear();
      for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const QVec &s = poly[j], &e = poly[i];
        if (inside(s) != inside(e)) {
          Q t = (plane - s[a]) / (e[a] - s[a]);
          QVec x;
          for (int b = 0; b < 3; ++b) x[b] = s[b] + t * (e[b] - s[b]);
          next.push_back(x);
        }
        if (inside(e)) next.push_back(e);
      }
      poly.swap(next);
      if (poly.empty()) return poly;
    }
  return poly;
}

// The exact bounds of a polygon; false when it is empty.
inline bool exact_bounds(const std::vector<QVec>& poly, QVec* lo, QVec* hi) {
  if (poly.empty()) return false;
  *lo = *hi = poly[0];
  for (const QVec& v : poly)
    for (int a = 0; a < 3; ++a) {
      if (v[a] < (*lo)[a]) (*lo)[a] = v[a];
      if (v[a] > (*hi)[a]) (*hi)[a] = v[a];
    }
  return true;
}

// The exact part [enter, exit] of the closed interval [tmin, tmax] in which the line o + t d lies in the
// closed box; false when it is empty. Infinite tmin or tmax count as unbounded (flags, as rationals cannot be
// infinite).
inline bool exact_slab_interval(const Bounds3& box, const glm::vec3& o, const glm::vec3& d, float tmin,
                                float tmax, Q* enter, Q* exit, bool* enter_unbounded, bool* exit_unbounded) {
  bool lo_free = std::isinf(tmin), hi_free = std::isinf(tmax);
  Q t0 = lo_free ? Q(0) : Q(double(tmin)), t1 = hi_free ? Q(0) : Q(double(tmax));
  for (int a = 0; a < 3; ++a) {
    Q oa(double(o[a])), lo(double(box.lo[a])), hi(double(box.hi[a]));
    if (d[a] == 0.f) {
      if (oa < lo || oa > hi) return false;
      continue;
    }
    Q da(double(d[a]));
    Q tn = (lo - oa) / da, tf = (hi - oa) / da;
    if (tn > tf) std::swap(tn, tf);
    if (lo_free || tn > t0) t0 = tn, lo_free = false;
    if (hi_free || tf < t1) t1 = tf, hi_free = false;
  }
  if (!lo_free && !hi_free && t0 > t1) return false;
  *enter = t0;
  *exit = t1;
  *enter_unbounded = lo_free;
  *exit_unbounded = hi_free;
  return true;
}

inline Q det(const QVec& a, const QVec& b, const QVec& c) {
  return dot(a, cross(b, c));
}

struct ExactHit {
  bool hit = false;
  Q t;                      // the exact distance when hit
  Q b[3];                   // the exact barycentrics of the line's point in the plane (when not parallel)
  int edge[3] = {0, 0, 0};  // signs of det[p_j - o, p_k - o, d] for the edges (1, 2), (2, 0), (0, 1)
};

// Does the ray o + t d, tmin < t (tmax = +inf), meet the closed triangle? Inside when the three edge
// determinants share a sign (zeros allowed) and are not all zero; t* = n.(p0 - o) / n.d must exceed tmin.
inline ExactHit exact_ray_triangle(const Ray& r, const glm::vec3& p0, const glm::vec3& p1,
                                   const glm::vec3& p2) {
  ExactHit h;
  QVec o = to_q(r.origin), d = to_q(r.direction), v0 = to_q(p0), v1 = to_q(p1), v2 = to_q(p2);
  QVec a = sub(v0, o), b = sub(v1, o), c = sub(v2, o);
  Q e[3] = {det(b, c, d), det(c, a, d), det(a, b, d)};
  for (int i = 0; i < 3; ++i) h.edge[i] = sgn(e[i]);
  Q sum = e[0] + e[1] + e[2];  // n . d
  if (sgn(sum) != 0)
    for (int i = 0; i < 3; ++i) h.b[i] = e[i] / sum;
  bool neg = h.edge[0] < 0 || h.edge[1] < 0 || h.edge[2] < 0;
  bool pos = h.edge[0] > 0 || h.edge[1] > 0 || h.edge[2] > 0;
  if (neg == pos || sgn(sum) == 0) return h;  // mixed signs, or all zero (the ray in the triangle's plane)
  h.t = det(a, b, c) / sum;
  h.hit = h.t > Q(double(r.tmin));
  return h;
}

}  // namespace raystep::test
