// Möller–Trumbore ray-triangle intersection (Möller and Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection", JGT 1997): Cramer's rule on o + t d = (1-u-v) p0 + u p1 + v p2 with scalar triple products.
// Kept as the fast, NON-watertight reference for the benchmarks and tests: each triangle computes its own
// barycentrics, so a ray through a shared edge can be rejected by both neighbours (a leak).
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/ray.h"
#include "raystep/geometry/triangle.h"

namespace raystep {

// Same contract as intersect_triangle: ray.tmin < t < tmax; *hit holds t and barycentrics (b0 = 1 - u - v).
// Edges count as inside (u >= 0, v >= 0, u + v <= 1); no epsilon: only an exactly parallel ray (det = 0)
// is rejected up front.
inline bool intersect_triangle_moller(const Ray& ray, const glm::vec3& p0, const glm::vec3& p1,
                                      const glm::vec3& p2, float tmax, TriangleHit* hit) {
  glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
  // Determinant of [-d, e1, e2]: d . (e1 x e2), computed as (d x e2) . e1.
  glm::vec3 pvec = glm::cross(ray.direction, e2);
  float det = glm::dot(e1, pvec);
  if (det == 0.f) return false;
  float inv_det = 1.f / det;
  // Barycentric u, then v, with early exits (the "minimum storage" order of the paper).
  glm::vec3 tvec = ray.origin - p0;
  float u = glm::dot(tvec, pvec) * inv_det;
  if (!(u >= 0.f && u <= 1.f)) return false;  // also rejects NaN
  glm::vec3 qvec = glm::cross(tvec, e1);
  float v = glm::dot(ray.direction, qvec) * inv_det;
  if (!(v >= 0.f && u + v <= 1.f)) return false;
  float t = glm::dot(e2, qvec) * inv_det;
  if (!(t > ray.tmin && t < tmax)) return false;
  hit->t = t;
  hit->b0 = 1.f - u - v;
  hit->b1 = u;
  hit->b2 = v;
  return true;
}

inline bool intersect_triangle_moller(const Ray& ray, const glm::vec3& p0, const glm::vec3& p1,
                                      const glm::vec3& p2, TriangleHit* hit) {
  return intersect_triangle_moller(ray, p0, p1, p2, ray.tmax, hit);
}

// Every value the test computes, without its early exits, for a debugger that shows why a ray was rejected:
// the same expressions in the same order, so the same float values. failed names the first condition the test
// rejects on, in its order ("det = 0", "u < 0", "u > 1", "v < 0", "u + v > 1", "t"), or is null on a hit.
struct MollerTrumboreValues {
  float det = 0.f, u = 0.f, v = 0.f, t = 0.f;
  const char* failed = nullptr;
};

inline MollerTrumboreValues moller_trumbore_values(const Ray& ray, const glm::vec3& p0, const glm::vec3& p1,
                                                   const glm::vec3& p2, float tmax) {
  MollerTrumboreValues m;
  glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
  glm::vec3 pvec = glm::cross(ray.direction, e2);
  m.det = glm::dot(e1, pvec);
  float inv_det = 1.f / m.det;
  glm::vec3 tvec = ray.origin - p0;
  m.u = glm::dot(tvec, pvec) * inv_det;
  glm::vec3 qvec = glm::cross(tvec, e1);
  m.v = glm::dot(ray.direction, qvec) * inv_det;
  m.t = glm::dot(e2, qvec) * inv_det;
  if (m.det == 0.f) m.failed = "det = 0";
  else if (!(m.u >= 0.f)) m.failed = "u < 0";
  else if (!(m.u <= 1.f)) m.failed = "u > 1";
  else if (!(m.v >= 0.f)) m.failed = "v < 0";
  else if (!(m.u + m.v <= 1.f)) m.failed = "u + v > 1";
  else if (!(m.t > ray.tmin && m.t < tmax)) m.failed = "t";
  return m;
}

}  // namespace raystep
