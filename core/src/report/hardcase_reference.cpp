#include "raystep/report/hardcase_reference.h"

#include <algorithm>
#include <cmath>

#include <glm/vec3.hpp>

#include "raystep/geometry/exact.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

using glm::dvec3;

// Rounding error bound of a 3x3 determinant of float differences in double, relative to its permanent:
// Shewchuk's orient3d bound is (7 eps + 56 eps^2) times the permanent; twice that, for margin.
constexpr double kDetBound = 16.0 * 1.1102230246251565e-16;

double det3(const dvec3& a, const dvec3& b, const dvec3& c) {
  return a.x * (b.y * c.z - b.z * c.y) + a.y * (b.z * c.x - b.x * c.z) + a.z * (b.x * c.y - b.y * c.x);
}
double perm3(const dvec3& a, const dvec3& b, const dvec3& c) {
  return std::fabs(a.x) * (std::fabs(b.y * c.z) + std::fabs(b.z * c.y)) +
         std::fabs(a.y) * (std::fabs(b.z * c.x) + std::fabs(b.x * c.z)) +
         std::fabs(a.z) * (std::fabs(b.x * c.y) + std::fabs(b.y * c.x));
}

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool valid_ray(const Ray& r) {
  return finite3(r.origin) && finite3(r.direction) && r.direction != glm::vec3(0.f) && !std::isnan(r.tmin) &&
         !std::isnan(r.tmax) && r.tmin < r.tmax;
}

enum class Crossing { miss, hit, boundary };

// The ray against one triangle: where it crosses (strictly inside, or on an edge or vertex), and t.
Crossing classify(const Ray& r, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                  double* t_out) {
  const dvec3 o(r.origin), d(r.direction);
  const dvec3 a = dvec3(p0) - o, b = dvec3(p1) - o, c = dvec3(p2) - o;
  // Edge determinants det[p_j - o, p_k - o, d] for the edges (1, 2), (2, 0), (0, 1).
  double e[3] = {det3(b, c, d), det3(c, a, d), det3(a, b, d)};
  double p[3] = {perm3(b, c, d), perm3(c, a, d), perm3(a, b, d)};
  int s[3];
  bool exact = false;
  for (int i = 0; i < 3; ++i) {
    if (std::fabs(e[i]) <= kDetBound * p[i]) exact = true;
    s[i] = e[i] > 0 ? 1 : (e[i] < 0 ? -1 : 0);
  }
  if (!exact && (std::min({s[0], s[1], s[2]}) < 0) && (std::max({s[0], s[1], s[2]}) > 0))
    return Crossing::miss;
  if (exact) edge_signs(p0, p1, p2, r.origin, r.direction, s);
  const bool neg = s[0] < 0 || s[1] < 0 || s[2]<0, pos = s[0]> 0 || s[1] > 0 || s[2] > 0;
  if (neg == pos) return Crossing::miss;  // mixed signs, or all zero (edge-on or degenerate)
  const bool on_boundary = s[0] == 0 || s[1] == 0 || s[2] == 0;

  double t;
  if (exact) {
    // The double determinants are not trusted here: t from the exact decision (core's exact path).
    float tf, b0, b1, b2;
    if (!exact_triangle_hit(p0, p1, p2, r.origin, r.direction, r.tmin, kInfinity, &tf, &b0, &b1, &b2))
      return Crossing::miss;
    t = tf;
  } else {
    const double den = e[0] + e[1] + e[2];  // n . d, of one sign with each term: no cancellation
    const double num = det3(a, b, c);
    t = num / den;
    // |error of num| <= kDetBound perm; den's relative error is a few eps: beyond the bound, t's side of
    // tmin is proven; within it (an origin on or next to the plane), decided exactly.
    const double err =
        (kDetBound * perm3(a, b, c) + std::fabs(num) * 8 * 1.1102230246251565e-16) / std::fabs(den);
    if (!(t - err > double(r.tmin))) {
      if (t + err < double(r.tmin) || !plane_hit_beyond(p0, p1, p2, r.origin, r.direction, r.tmin))
        return Crossing::miss;
    }
  }
  if (!(t < double(r.tmax))) return Crossing::miss;
  *t_out = t;
  return on_boundary ? Crossing::boundary : Crossing::hit;
}

double max_abs(const glm::vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

}  // namespace

bool reference_triangle_hit(const Ray& ray, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                            double* t) {
  if (!valid_ray(ray)) return false;
  return classify(ray, p0, p1, p2, t) != Crossing::miss;
}

ReferenceHit reference_nearest(const Geometry& g, const Ray& ray) {
  if (!g.all_triangles()) throw InputError("", 0, "hard cases: the reference handles triangles only");
  ReferenceHit ref;
  if (!valid_ray(ray)) return ref;
  struct Candidate {
    int32_t id;
    double t, tol;
  };
  std::vector<Candidate> hits;
  const double inv_d = 1.0 / max_abs(ray.direction);
  const double m_o = max_abs(ray.origin);
  for (uint32_t id = 0; id < g.size(); ++id) {
    const glm::vec3 &p0 = g.vertex(id, 0), &p1 = g.vertex(id, 1), &p2 = g.vertex(id, 2);
    double t;
    if (classify(ray, p0, p1, p2, &t) == Crossing::miss) continue;
    const double m = std::max({m_o, max_abs(p0), max_abs(p1), max_abs(p2)});
    hits.push_back({int32_t(id), t, std::ldexp(std::fabs(t) + m * inv_d, -16)});
  }
  if (hits.empty()) return ref;
  const Candidate nearest = *std::min_element(
      hits.begin(), hits.end(), [](const Candidate& x, const Candidate& y) { return x.t < y.t; });
  ref.hit = true;
  ref.t = nearest.t;
  for (const Candidate& c : hits)
    if (c.t <= nearest.t + nearest.tol + c.tol) ref.tied.push_back(c.id);
  return ref;
}

bool agrees_with_reference(const ReferenceHit& reference, const Hit& hit) {
  if (!reference.hit) return !hit.found();
  if (!hit.found()) return false;
  return std::binary_search(reference.tied.begin(), reference.tied.end(), hit.prim);
}

int crossing_parity(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                    const Ray& ray) {
  if (!valid_ray(ray)) return -1;
  int count = 0;
  for (const glm::uvec3& tri : triangles) {
    double t;
    Crossing c = classify(ray, positions[tri[0]], positions[tri[1]], positions[tri[2]], &t);
    if (c == Crossing::boundary) return -1;
    count += c == Crossing::hit;
  }
  return count & 1;
}

}  // namespace raystep
