// Axis-aligned bounding box and the slab test (Kay and Kajiya 1986) made robust:
// near/far planes chosen by the sign bit of the reciprocal direction (Williams et al. 2005), so +0 and -0
// components behave alike; a 0*inf NaN (ray lying in a slab plane) adds no constraint; rays with NaN
// components miss; the entry and exit distances are moved outward by Ize's factor 1 -+ 2*gamma(3)
// (Ize, "Robust BVH Ray Traversal", JCGT 2013) whatever their signs, so that the test is conservative.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"

namespace raystep {

struct Bounds3 {
  glm::vec3 lo{kInfinity};
  glm::vec3 hi{-kInfinity};

  Bounds3() = default;
  Bounds3(const glm::vec3& a, const glm::vec3& b) : lo(glm::min(a, b)), hi(glm::max(a, b)) {}

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void extend(const Bounds3& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.f) : hi - lo; }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  // Surface area: with Crofton's theorem, the probability that a random line through a convex parent
  // also passes through a convex child is S_child / S_parent.
  float surface_area() const {
    glm::vec3 e = extent();
    return 2.f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  int max_axis() const {
    glm::vec3 e = extent();
    return (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
  }
  bool contains(const glm::vec3& p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  bool overlaps(const Bounds3& b) const {
    return lo.x <= b.hi.x && hi.x >= b.lo.x && lo.y <= b.hi.y && hi.y >= b.lo.y && lo.z <= b.hi.z &&
           hi.z >= b.lo.z;
  }
};

inline Bounds3 union_of(Bounds3 a, const Bounds3& b) {
  a.extend(b);
  return a;
}

inline bool is_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A ray prepared for many slab tests: the reciprocal direction is computed once.
// valid is false for rays that can hit nothing: NaN or infinite origin, NaN or zero direction,
// NaN tmin/tmax or an empty interval.
struct SlabRay {
  glm::vec3 origin;
  glm::vec3 inv_dir;
  float tmin, tmax;
  bool valid;

  explicit SlabRay(const Ray& r)
      : origin(r.origin), inv_dir(1.f / r.direction.x, 1.f / r.direction.y, 1.f / r.direction.z),
        tmin(r.tmin), tmax(r.tmax) {
    const glm::vec3& d = r.direction;
    bool finite_dir = std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z);
    bool nonzero_dir = d.x != 0.f || d.y != 0.f || d.z != 0.f;
    valid = is_finite(r.origin) && finite_dir && nonzero_dir && !std::isnan(r.tmin) && !std::isnan(r.tmax) &&
            r.tmin < r.tmax;
  }
};

// Slab test. On a hit, [*t_enter, *t_exit] contains the part of [ray.tmin, ray.tmax] inside the box, widened by
// at most 2*gamma(3) of each plane distance (touching the box's boundary counts as a hit: the box is closed).
// Never a miss when the exact segment meets the box (for normal, not subnormal, floats).
inline bool intersect_slabs(const Bounds3& b, const SlabRay& r, float* t_enter, float* t_exit) {
  if (!r.valid) return false;
  float t0 = r.tmin, t1 = r.tmax;
  for (int a = 0; a < 3; ++a) {
    // Near and far planes by the sign bit, so that -0 selects the same planes as a negative direction.
    bool negative = std::signbit(r.inv_dir[a]);
    float t_near = ((negative ? b.hi[a] : b.lo[a]) - r.origin[a]) * r.inv_dir[a];
    float t_far = ((negative ? b.lo[a] : b.hi[a]) - r.origin[a]) * r.inv_dir[a];
    // Ize's factor, for every sign. Each distance is within gamma(3)|t| of the exact one (a subtraction, the
    // rounded reciprocal, a product); scaling t_near towards -inf and t_far towards +inf by 2*gamma(3) (as a
    // float, 6 ulps of 1: enough for the product's own rounding too) makes them bounds of the exact ones, so
    // [t0, t1] contains the exact interval. Scaling by 1 + 2*gamma(3) alone moved a negative t_far inwards
    // (a box behind the origin, or an origin inside near a face, with tmin < 0: a line's overlap was lost),
    // and left t_near free to round above an exit or tmax. Infinities keep their sign; NaN stays NaN.
    t_near *= t_near > 0.f ? 1.f - 2.f * gamma(3) : 1.f + 2.f * gamma(3);
    t_far *= t_far > 0.f ? 1.f + 2.f * gamma(3) : 1.f - 2.f * gamma(3);
    // Written so that a NaN (0*inf: the ray lies in this slab's plane) leaves t0, t1 unchanged.
    t0 = t_near > t0 ? t_near : t0;
    t1 = t_far < t1 ? t_far : t1;
    if (t0 > t1) return false;
  }
  // A parallel ray outside a slab gets t_near = +inf; with tmax = +inf that must still be a miss.
  if (t0 == kInfinity) return false;
  if (t_enter) *t_enter = t0;
  if (t_exit) *t_exit = t1;
  return true;
}

inline bool intersect_slabs(const Bounds3& b, const Ray& r, float* t_enter = nullptr, float* t_exit = nullptr) {
  return intersect_slabs(b, SlabRay(r), t_enter, t_exit);
}

}  // namespace raystep
