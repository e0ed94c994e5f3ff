// Ray-sphere intersection with a numerically stable quadratic, after Haines et al., "Precision Improvements
// for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): work relative to the centre in double, take the
// discriminant from the distance of the centre to the ray's line (no catastrophic cancellation at grazing
// angles or far from the origin), and form the two roots without subtracting nearly equal numbers. A ray from
// inside always finds the sphere, and a root beyond tmin is a hit even where it rounds to tmin in float.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"

namespace raystep {

struct Sphere {
  glm::vec3 center{0.f};
  float radius = 1.f;
};

// Nearest root t of |o + t d - c| = r with tmin < t < tmax.
inline bool intersect_sphere(const Ray& ray, const Sphere& s, float tmax, float* t_hit) {
  glm::dvec3 f = glm::dvec3(ray.origin) - glm::dvec3(s.center);
  glm::dvec3 d(ray.direction);
  double r = s.radius;
  double a = glm::dot(d, d);
  double b = -glm::dot(f, d);  // the quadratic is a t^2 - 2 b t + c = 0
  double c = glm::dot(f, f) - r * r;
  // Discriminant a(r^2 - |f + (b/a) d|^2): the squared distance of the centre to the line, computed directly.
  glm::dvec3 l = f + (b / a) * d;
  double disc = a * (r * r - glm::dot(l, l));
  // The exact discriminant is b^2 - a c >= -a c: from inside (c < 0) the line always meets the sphere, also
  // where the rounding of |l|^2 (origin next to the surface: r^2 - |f|^2 of a few ulps of r^2) says otherwise.
  disc = std::max(disc, -a * c);
  if (!(disc >= 0.0)) return false;  // also rejects NaN
  // Stable roots: q = b + sign(b) sqrt(disc); t0 = c/q, t1 = q/a (of opposite signs when c < 0).
  double q = b + std::copysign(std::sqrt(disc), b);
  double t0 = c / q, t1 = q / a;
  if (q == 0.0) t0 = t1 = 0.0;  // c = 0 and b = 0: the origin is on the sphere, the ray tangent
  if (t0 > t1) std::swap(t0, t1);
  // Beyond tmin is decided on the double roots: a root just above tmin may round to tmin itself as a float, and
  // the float comparison skipped that hit (for the far root, or a miss). It is reported at the next float above
  // tmin, as the triangle test does; tmax is compared in float, as every structure compares its hits.
  const double tmin = ray.tmin;
  const double t = t0 > tmin ? t0 : t1;
  if (!(t > tmin)) return false;
  float ft = float(t);
  if (!(ft > ray.tmin)) ft = next_float_up(ray.tmin);
  if (!(ft < tmax)) return false;
  *t_hit = ft;
  return true;
}

// Hit point reprojected onto the sphere, and its absolute error bound per axis (pbrt-v4, 6.8.5),
// widened by the rounding of adding the centre back.
inline glm::vec3 sphere_point(const Ray& ray, const Sphere& s, float t, glm::vec3* p_error) {
  glm::dvec3 local = glm::dvec3(ray.origin) + double(t) * glm::dvec3(ray.direction) - glm::dvec3(s.center);
  double len = glm::length(local);
  if (len > 0) local *= double(s.radius) / len;
  glm::vec3 p = glm::vec3(glm::dvec3(s.center) + local);
  *p_error = gamma(5) * glm::abs(glm::vec3(local)) + gamma(2) * (glm::abs(s.center) + glm::abs(p));
  return p;
}

}  // namespace raystep
