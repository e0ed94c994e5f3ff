// Discrete oriented polytopes: an object bounded by slab pairs lo_k <= n_k . p <= hi_k along chosen
// directions, and the slab test of a ray against them (Kay and Kajiya 1986; k-DOPs: Klosowski et al. 1998).
// The 7 slab pairs of the 3 axes and the 4 body diagonals make the 14-DOP; the 3 principal axes of an
// object's points (PCA) make its oriented box. Worked in double with error bounds: never a miss for a ray
// whose exact segment meets the polytope.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"
#include "raystep/geometry/sphere.h"

namespace raystep {

// The k-DOP's directions: the 3 axes, then the 4 body diagonals (not normalised: n . p is a sum of
// coordinates).
inline const std::array<glm::dvec3, 7>& kdop_directions() {
  static const std::array<glm::dvec3, 7> dirs = {
      glm::dvec3(1, 0, 0),  glm::dvec3(0, 1, 0),  glm::dvec3(0, 0, 1), glm::dvec3(1, 1, 1),
      glm::dvec3(1, 1, -1), glm::dvec3(1, -1, 1), glm::dvec3(-1, 1, 1)};
  return dirs;
}

// The slab [lo, hi] of n . p over the points and spheres, rounded outwards by the error bound of each dot
// product: every point satisfies lo <= n . p <= hi exactly. Empty input: lo = +inf, hi = -inf.
void fit_slab(const glm::dvec3& n, const std::vector<glm::vec3>& points, const std::vector<Sphere>& spheres,
              double* lo, double* hi);

// Three orthonormal directions: the eigenvectors of the points' covariance (principal component analysis),
// by Jacobi rotations. Degenerate sets (one point, collinear, coplanar) still get an orthonormal frame.
std::array<glm::dvec3, 3> principal_axes(const std::vector<glm::vec3>& points);

// A ray prepared for the slabs of one direction n: the origin's n . o and the direction's n . d with their
// error bounds. When the sign of n . d cannot be proven the slab is not used (no constraint: conservative);
// when n . d is exactly 0 the ray stays in one plane n . p = n . o.
struct SlabLine {
  enum Mode : uint8_t { crossing, parallel, unknown };
  double no = 0.0, e_no = 0.0;    // n . o and its error bound
  double inv = 0.0, e_inv = 0.0;  // 1 / (n . d) and its relative error bound
  Mode mode = unknown;

  SlabLine() = default;
  SlabLine(const glm::dvec3& n, const Ray& r) {
    const glm::dvec3 o(r.origin), d(r.direction);
    no = glm::dot(n, o);
    e_no = gamma_double(4) * (std::abs(n.x * o.x) + std::abs(n.y * o.y) + std::abs(n.z * o.z));
    const double nd = glm::dot(n, d);
    const double e_nd = gamma_double(4) * (std::abs(n.x * d.x) + std::abs(n.y * d.y) + std::abs(n.z * d.z));
    if (nd == 0.0 && e_nd == 0.0) {
      mode = parallel;
    } else if (std::abs(nd) > e_nd) {
      mode = crossing;
      inv = 1.0 / nd;
      e_inv = e_nd / (std::abs(nd) - e_nd) + gamma_double(2);
    }
  }
};

// Clips [*t0, *t1] to the slab lo <= n . p <= hi; false when the interval becomes empty. Each distance
// (plane - n . o) / (n . d) is moved outwards by its error bound.
inline bool clip_slab(const SlabLine& s, double lo, double hi, double* t0, double* t1) {
  if (!(lo <= hi)) return false;  // an object without primitives
  if (s.mode == SlabLine::unknown) return true;
  if (s.mode == SlabLine::parallel) return s.no + s.e_no >= lo && s.no - s.e_no <= hi;
  const double near_plane = s.inv > 0.0 ? lo : hi, far_plane = s.inv > 0.0 ? hi : lo;
  const double n_near = near_plane - s.no, n_far = far_plane - s.no;
  const double t_near = n_near * s.inv, t_far = n_far * s.inv;
  const double a_inv = std::abs(s.inv);
  // |t - t_exact| <= |1/nd| ((|N| + e_no) e_inv + e_no) + the rounding of the subtraction and product.
  const double err_near =
      (a_inv * ((std::abs(n_near) + s.e_no) * s.e_inv + s.e_no) + gamma_double(3) * std::abs(t_near)) *
      (1.0 + gamma_double(4));
  const double err_far =
      (a_inv * ((std::abs(n_far) + s.e_no) * s.e_inv + s.e_no) + gamma_double(3) * std::abs(t_far)) *
      (1.0 + gamma_double(4));
  *t0 = std::max(*t0, t_near - err_near);
  *t1 = std::min(*t1, t_far + err_far);
  return *t0 <= *t1;
}

// The entry and exit in float: rounded outwards and widened like a slab distance (bounds.h), so that the
// entry is as safe a lower bound on an object's hit t as a box's.
inline bool slab_interval_to_float(double t0, double t1, float tmin, float* t_enter, float* t_exit) {
  if (!(t0 <= t1)) return false;
  float f0 = float(t0), f1 = float(t1);
  if (double(f0) > t0) f0 = next_float_down(f0);
  if (double(f1) < t1) f1 = next_float_up(f1);
  f0 *= f0 > 0.f ? 1.f - 2.f * gamma(3) : 1.f + 2.f * gamma(3);
  f1 *= f1 > 0.f ? 1.f + 2.f * gamma(3) : 1.f - 2.f * gamma(3);
  if (f0 == kInfinity) return false;
  *t_enter = std::max(f0, tmin);
  *t_exit = f1;
  return true;
}

}  // namespace raystep
