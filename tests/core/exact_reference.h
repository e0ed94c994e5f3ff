// The ray-triangle question answered in exact rational arithmetic (GMP) on the float inputs: the reference
// that the watertight test and the exact predicates (exact.h) are checked against on hard cases.
#pragma once

#include <gmpxx.h>

#include <glm/vec3.hpp>

#include "raystep/geometry/ray.h"

namespace raystep::test {

struct ExactVec {
  mpq_class x, y, z;
  explicit ExactVec(const glm::vec3& v) : x(double(v.x)), y(double(v.y)), z(double(v.z)) {}
  ExactVec(mpq_class a, mpq_class b, mpq_class c) : x(std::move(a)), y(std::move(b)), z(std::move(c)) {}
};
inline ExactVec operator-(const ExactVec& a, const ExactVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline mpq_class dot(const ExactVec& a, const ExactVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline ExactVec cross(const ExactVec& a, const ExactVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline mpq_class det(const ExactVec& a, const ExactVec& b, const ExactVec& c) { return dot(a, cross(b, c)); }

struct ExactHit {
  bool hit = false;
  mpq_class t;     // the exact distance when hit
  mpq_class b[3];  // the exact barycentrics of the line's point in the plane (when it is not parallel)
  int edge[3] = {0, 0, 0};  // signs of det[p_j - o, p_k - o, d] for edges (1,2), (2,0), (0,1)
};

// Does the line o + t d, tmin < t (tmax = +inf), meet the closed triangle? Inside when the three edge
// determinants share a sign (zeros allowed) and are not all zero; t* = n.(p0 - o) / n.d must exceed tmin.
inline ExactHit exact_ray_triangle(const Ray& r, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  ExactHit h;
  ExactVec o(r.origin), d(r.direction), v0(p0), v1(p1), v2(p2);
  ExactVec a = v0 - o, b = v1 - o, c = v2 - o;
  mpq_class e[3] = {det(b, c, d), det(c, a, d), det(a, b, d)};
  for (int i = 0; i < 3; ++i) h.edge[i] = sgn(e[i]);
  mpq_class sum = e[0] + e[1] + e[2];  // n . d
  if (sgn(sum) != 0)
    for (int i = 0; i < 3; ++i) h.b[i] = e[i] / sum;
  bool neg = h.edge[0] < 0 || h.edge[1] < 0 || h.edge[2] < 0;
  bool pos = h.edge[0] > 0 || h.edge[1] > 0 || h.edge[2] > 0;
  if (neg == pos) return h;  // mixed signs, or all zero (the ray in the triangle's plane)
  ExactVec n = cross(v1 - v0, v2 - v0);
  mpq_class den = dot(n, d);
  if (sgn(den) == 0) return h;
  h.t = dot(n, a) / den;
  h.hit = h.t > mpq_class(double(r.tmin));
  return h;
}

}  // namespace raystep::test
