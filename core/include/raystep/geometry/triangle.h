// Watertight ray-triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection",
// JCGT 2013), in the form of pbrt-v4 (section 6.5.3): translate to the ray origin, permute so that the
// dominant direction axis is z, shear so the ray is +z, then evaluate the three 2D edge functions,
// each trusted only beyond its rounding error bound. Rays through a shared edge or vertex hit at least one of
// the triangles that share it. Whether the hit lies beyond tmin is decided by pbrt-v4's error bound on t
// (section 6.8.7) where the bound proves it either way. Where a bound cannot decide (a ray within rounding of
// an edge's line, a hit within delta_t of tmin: a long thin triangle seen from nearby), the answer is settled
// exactly (exact.h): a hit that cannot be proven is still a hit, and the exact line's triangle is the one
// found.
#pragma once

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/component.h"
#include "raystep/geometry/exact.h"
#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"

namespace raystep {

// The per-ray part of the test, computed once per ray: axis permutation and shear.
struct WatertightRay {
  glm::vec3 origin;
  int kx, ky, kz;
  float sx, sy, sz;
  float shear_x, shear_y;  // 2 |sx|, 2 |sy|: how much of a vertex's z enters the error of its sheared x, y
  int dz_sign;             // the sign of the dominant direction component
  float tmin, tmax;
  glm::vec3 direction;  // for the exact decision, when the error bound cannot settle one

  explicit WatertightRay(const Ray& r)
      : origin(r.origin), tmin(r.tmin), tmax(r.tmax), direction(r.direction) {
    glm::vec3 ad = glm::abs(r.direction);
    kz = (ad.x > ad.y) ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    kx = kz + 1 == 3 ? 0 : kz + 1;
    ky = kx + 1 == 3 ? 0 : kx + 1;
    glm::vec3 d(r.direction[kx], r.direction[ky], r.direction[kz]);
    sx = -d.x / d.z;
    sy = -d.y / d.z;
    sz = 1.f / d.z;
    // A direction that is not finite meets nothing: a NaN scale makes every t NaN, which no test accepts.
    if (!(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z))) sz = std::nanf("");
    dz_sign = d.z > 0 ? 1 : -1;
    shear_x = 2.f * std::fabs(sx);
    shear_y = 2.f * std::fabs(sy);
  }
};

struct TriangleHit {
  float t;
  float b0, b1, b2;  // barycentric coordinates: p = b0*p0 + b1*p1 + b2*p2
};

namespace detail {
// Largest of |x|, |y|, |z| by plain comparisons: std::fmax is a library call unless NaNs are ruled out at
// compile time (-ffast-math), and twelve such calls made a hit cost seven times a miss.
inline float max_abs3(float x, float y, float z) {
  x = std::fabs(x), y = std::fabs(y), z = std::fabs(z);
  float m = x > y ? x : y;
  return m > z ? m : z;
}

// The test for one permutation (kx, ky, kz) of the axes, fixed at compile time so that every component is
// read from a register (a permutation known only at run time goes through memory on each test).
// Always inlined: its slow paths (calls into exact.h) made it large enough that the compiler stopped inlining
// it into the traversal loops, which then cost a call per test (+33% instructions on a grid render).
template <int kx, int ky, int kz>
[[gnu::always_inline]] inline bool intersect_triangle_permuted(const WatertightRay& r, const glm::vec3& p0,
                                                               const glm::vec3& p1, const glm::vec3& p2,
                                                               float tmax, TriangleHit* hit) {
  // Translate the vertices to the ray origin, permute (kx, ky, kz) and shear so the ray runs along +z.
  glm::vec3 a = p0 - r.origin, b = p1 - r.origin, c = p2 - r.origin;
  float ax = component(a, kx) + r.sx * component(a, kz), ay = component(a, ky) + r.sy * component(a, kz);
  float bx = component(b, kx) + r.sx * component(b, kz), by = component(b, ky) + r.sy * component(b, kz);
  float cx = component(c, kx) + r.sx * component(c, kz), cy = component(c, ky) + r.sy * component(c, kz);

  // Edge functions: signed areas of the sheared triangle's edges seen from the ray (the origin in 2D).
  float e0 = bx * cy - by * cx;
  float e1 = cx * ay - cy * ax;
  float e2 = ax * by - ay * bx;

  // A conservative bound delta_e on each edge function's rounding error (after pbrt-v4, 6.8.7): an edge
  // function larger than it has the sign of the exact determinant det[p_j - o, p_k - o, d] / d_z. The sheared
  // x' = x + sx z carries the roundings of the translation, of sx itself, of the product and of the sum: at
  // most gamma(6) (|x'| + 2 |sx z|), with z the translated z BEFORE scaling by sz (pbrt-v4's code reuses the
  // scaled one, and bounds |sx z| by |z|, which is loose for a ray nearly along its dominant axis).
  float max_z = max_abs3(component(a, kz), component(b, kz), component(c, kz));
  float max_xt = max_abs3(ax, bx, cx);
  float max_yt = max_abs3(ay, by, cy);
  float delta_x = gamma(6) * (max_xt + r.shear_x * max_z);
  float delta_y = gamma(6) * (max_yt + r.shear_y * max_z);
  float delta_e = 2 * (gamma(3) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
  // The conditions below combine their comparisons with | and &, not || and &&: each short-circuit operator
  // is a branch of its own, and on a miss which edge function decides it is a coin toss for the predictor
  // (one branch instead of up to six: 12-16% faster kd-tree and grid walks on the bunny, bench/README.md).
  if (__builtin_expect(
          int(std::fabs(e0) <= delta_e) | int(std::fabs(e1) <= delta_e) | int(std::fabs(e2) <= delta_e), 0)) {
    // The ray passes within rounding of an edge's line (or through it, or a vertex): the float edge functions
    // cannot be trusted there, so the test is settled exactly (exact.h). A ray through a long thin triangle's
    // edge then finds the triangle the exact line meets, not its neighbour, which the structures may not hold
    // in the cell or leaf the ray is in at that point.
    return exact_triangle_hit(p0, p1, p2, r.origin, r.direction, r.tmin, tmax, &hit->t, &hit->b0, &hit->b1,
                              &hit->b2);
  } else if (((e0 < 0) | (e1 < 0) | (e2 < 0)) & ((e0 > 0) | (e1 > 0) | (e2 > 0))) {
    return false;  // the origin is outside: the edge functions differ in sign
  }
  // Inside: all edge functions share a sign (each exceeds its error bound, so none is zero).
  float det = e0 + e1 + e2;

  // Scaled hit distance, compared with tmax without dividing: beyond tmax (the nearest hit so far, for an
  // accelerator) is decided in float, as every structure compares its hits.
  float az = r.sz * component(a, kz), bz = r.sz * component(b, kz), cz = r.sz * component(c, kz);
  float t_scaled = e0 * az + e1 * bz + e2 * cz;
  if (((det < 0) & (t_scaled < tmax * det)) | ((det > 0) & (t_scaled > tmax * det))) return false;
  float inv_det = 1.f / det;
  float t = t_scaled * inv_det;
  if (!(t < tmax)) return false;

  // Beyond tmin? A conservative bound delta_t on the rounding error of t (pbrt-v4, 6.8.7) decides it where
  // t lies further than delta_t from tmin.
  float max_zt = max_abs3(az, bz, cz);
  float delta_z = gamma(3) * max_zt;
  float max_e = max_abs3(e0, e1, e2);
  float delta_t = 3 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * std::fabs(inv_det);
  // delta_t bounds the error of t near 0, where det's own error cannot change t's sign; away from 0 that
  // error (each edge function's delta_e, and the division) moves t in proportion to it.
  if (__builtin_expect(r.tmin != 0.f, 0))
    delta_t += std::fabs(t) * (gamma(4) + 3 * delta_e * std::fabs(inv_det));
  // Written so that a NaN bound goes to the exact decision too.
  if (__builtin_expect(!(t - delta_t > r.tmin), 0)) {
    if (t + delta_t < r.tmin) return false;  // proven before tmin (rounding is monotonic)
    // Not proven either way (a long thin triangle seen from nearby, an origin on or next to the surface):
    // settled exactly, and the hit's t and barycentrics computed again in double, since they are as loose as
    // the bound was. The edge functions are all proven, so their sum has the sign of n . d / d_z. (A tail
    // call: no value of this function lives across it, so its fast path keeps its registers in the walks it
    // is inlined in.)
    return settle_triangle_hit(p0, p1, p2, r.origin, r.direction, (det > 0 ? 1 : -1) * r.dz_sign, r.tmin,
                               tmax, &hit->t, &hit->b0, &hit->b1, &hit->b2);
  }

  hit->t = t;
  hit->b0 = e0 * inv_det;
  hit->b1 = e1 * inv_det;
  hit->b2 = e2 * inv_det;
  return true;
}
}  // namespace detail

// True if the ray hits triangle (p0, p1, p2) with ray.tmin < t < tmax; then *hit holds t and barycentrics.
// tmax is passed apart from the ray so that accelerators can shrink it as nearer hits are found. The branch
// on the ray's dominant axis goes the same way for every test of a ray, so the predictor learns it at once.
// intersect_triangle_inline is the same test forced inline, for a walk whose loop the compiler would
// otherwise leave calling it (the uniform grid's: callgrind, bench/README.md); forced everywhere it makes the
// trees' walks larger, so the others keep the compiler's choice.
[[gnu::always_inline]] inline bool intersect_triangle_inline(const WatertightRay& r, const glm::vec3& p0,
                                                             const glm::vec3& p1, const glm::vec3& p2,
                                                             float tmax, TriangleHit* hit) {
  switch (r.kz) {
    case 0:
      return detail::intersect_triangle_permuted<1, 2, 0>(r, p0, p1, p2, tmax, hit);
    case 1:
      return detail::intersect_triangle_permuted<2, 0, 1>(r, p0, p1, p2, tmax, hit);
    default:
      return detail::intersect_triangle_permuted<0, 1, 2>(r, p0, p1, p2, tmax, hit);
  }
}
inline bool intersect_triangle(const WatertightRay& r, const glm::vec3& p0, const glm::vec3& p1,
                               const glm::vec3& p2, float tmax, TriangleHit* hit) {
  return intersect_triangle_inline(r, p0, p1, p2, tmax, hit);
}

inline bool intersect_triangle(const Ray& ray, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                               TriangleHit* hit) {
  return intersect_triangle(WatertightRay(ray), p0, p1, p2, ray.tmax, hit);
}

// Hit point from barycentrics and its absolute error bound per axis (pbrt-v4, 6.8.5): gamma(7)*sum|b_i p_i|.
inline glm::vec3 triangle_point(const TriangleHit& h, const glm::vec3& p0, const glm::vec3& p1,
                                const glm::vec3& p2, glm::vec3* p_error) {
  glm::vec3 abs_sum = glm::abs(h.b0 * p0) + glm::abs(h.b1 * p1) + glm::abs(h.b2 * p2);
  *p_error = gamma(7) * abs_sum;
  return h.b0 * p0 + h.b1 * p1 + h.b2 * p2;
}

// Geometric normal (p1 - p0) x (p2 - p0), not normalised.
inline glm::vec3 triangle_normal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  return glm::cross(p1 - p0, p2 - p0);
}

}  // namespace raystep
