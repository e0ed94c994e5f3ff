// The smallest sphere around a set of points: Welzl's randomized algorithm ("Smallest enclosing disks (balls
// and ellipsoids)", 1991) in the move-to-front form of Gaertner's Miniball (ESA 1999), in double precision;
// and the ray test of a bounding sphere made conservative by error bounds, as the slab test is (bounds.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"
#include "raystep/geometry/sphere.h"

namespace raystep {

// A ball in double precision; radius < 0: the empty ball (no points).
struct Ball {
  glm::dvec3 center{0.0};
  double radius = -1.0;
};

// The smallest ball containing every point (up to rounding: every point lies within a relative 1e-12 of its
// radius). Points are shuffled with a fixed seed, so the same set always gives the same ball; the expected
// time is linear. Degenerate sets are fine: one point, duplicates, collinear, coplanar or cospherical points
// (a support that is numerically degenerate is replaced by the smallest ball of its subsets).
Ball minimal_ball(std::vector<glm::dvec3> points, uint64_t seed = 1);

// The smallest ball of at most four points, by trying the ball through every subset (pairs, triples, all
// four) and keeping the smallest that holds them all: the base case of Welzl's recursion when a support is
// degenerate.
Ball minimal_ball_of_few(const glm::dvec3* points, int count);

// A float sphere around an object: the minimal ball of its points and of the spheres' extreme points, with
// the centre rounded to float and the radius grown (and rounded up) until every point and every sphere lies
// inside exactly. Spheres in the list (a sphere primitive) are contained whole.
Sphere bounding_sphere(const std::vector<glm::vec3>& points, const std::vector<Sphere>& spheres);

// The ray against a bounding sphere, conservatively: [*t_enter, *t_exit] contains the part of
// [ray.tmin, ray.tmax] inside the ball; a ray whose exact segment meets the ball is never a miss. Worked in
// double relative to the centre (as intersect_sphere does) and widened by the error bound of each step, then
// by the slab test's 2 gamma(3) (so the entry is as safe a lower bound on an object's hit t as a box's).
// The caller checks that the ray is valid (SlabRay::valid).
inline bool intersect_bounding_sphere(const Sphere& s, const Ray& ray, float* t_enter, float* t_exit) {
  const glm::dvec3 f = glm::dvec3(ray.origin) - glm::dvec3(s.center);
  const glm::dvec3 d(ray.direction);
  const double a = glm::dot(d, d);
  const double len_d = std::sqrt(a);
  // The closest point of the line to the centre is at t_c = -f.d / |d|^2; l is the centre's offset from it.
  const double t_c = -glm::dot(f, d) / a;
  const glm::dvec3 l = f + t_c * d;
  const double f1 = std::abs(f.x) + std::abs(f.y) + std::abs(f.z);
  // Each of f's components is within an ulp of exact; t_c within gamma(12) |f| / |d| and each component of l
  // within gamma(14) 2 |f| (its terms are at most |f| each): generous bounds, a few 1e-15 of |f|.
  const double err_tc = gamma_double(16) * f1 / len_d;
  const double err_l = gamma_double(24) * 4.0 * f1;
  const double dist = glm::length(l);
  const double r = double(s.radius) + err_l;
  const double dist_lo = std::max(0.0, dist - err_l);
  if (!(dist_lo <= r)) return false;  // also NaN
  // Half the chord, overestimated: sqrt(r^2 - dist^2) / |d| with the larger r and the smaller distance.
  const double half = std::sqrt((r - dist_lo) * (r + dist_lo)) / len_d * (1.0 + gamma_double(8));
  double t0 = t_c - half - err_tc, t1 = t_c + half + err_tc;
  t0 -= gamma_double(2) * std::abs(t0);
  t1 += gamma_double(2) * std::abs(t1);
  // Clip to the ray's interval, in double; then to float, rounded outwards and widened like a slab distance.
  t0 = std::max(t0, double(ray.tmin));
  t1 = std::min(t1, double(ray.tmax));
  if (!(t0 <= t1)) return false;
  float ft0 = float(t0), ft1 = float(t1);
  if (double(ft0) > t0) ft0 = next_float_down(ft0);
  if (double(ft1) < t1) ft1 = next_float_up(ft1);
  ft0 *= ft0 > 0.f ? 1.f - 2.f * gamma(3) : 1.f + 2.f * gamma(3);
  ft1 *= ft1 > 0.f ? 1.f + 2.f * gamma(3) : 1.f - 2.f * gamma(3);
  if (ft0 == kInfinity) return false;
  *t_enter = std::max(ft0, ray.tmin);
  *t_exit = ft1;
  return true;
}

}  // namespace raystep
