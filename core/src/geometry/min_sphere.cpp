#include "raystep/geometry/min_sphere.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

namespace raystep {

namespace {

// Inside up to a relative 1e-12 of the radius: a point on the sphere through the support, which rounding
// puts a hair outside, must not be taken into the support (it would be degenerate with it).
bool holds(const Ball& b, const glm::dvec3& p) {
  if (b.radius < 0.0) return false;
  const glm::dvec3 v = p - b.center;
  return glm::dot(v, v) <= b.radius * b.radius * (1.0 + 2e-12);
}

bool holds_all(const Ball& b, const glm::dvec3* p, int n) {
  for (int i = 0; i < n; ++i)
    if (!holds(b, p[i])) return false;
  return true;
}

// The smallest ball with p and q on its boundary.
Ball diametral(const glm::dvec3& p, const glm::dvec3& q) {
  Ball b;
  b.center = 0.5 * (p + q);
  b.radius = 0.5 * glm::distance(p, q);
  return b;
}

// The smallest ball with p0, p1, p2 on its boundary: centred on their circumcircle. False when the three are
// collinear up to rounding (sin of the angle at p0 below 1e-12).
bool circumball(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, Ball* b) {
  const glm::dvec3 u = p1 - p0, v = p2 - p0;
  const glm::dvec3 w = glm::cross(u, v);
  const double ww = glm::dot(w, w), uu = glm::dot(u, u), vv = glm::dot(v, v);
  if (!(ww > 1e-24 * uu * vv)) return false;
  const glm::dvec3 offset = glm::cross(uu * v - vv * u, w) / (2.0 * ww);
  b->center = p0 + offset;
  b->radius = glm::length(offset);
  return true;
}

// The ball with the four points on its boundary (their circumsphere). False when they are coplanar up to
// rounding.
bool circumball(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& p3,
                Ball* b) {
  const glm::dvec3 u1 = p1 - p0, u2 = p2 - p0, u3 = p3 - p0;
  const double det = glm::dot(u1, glm::cross(u2, u3));
  const double scale = glm::length(u1) * glm::length(u2) * glm::length(u3);
  if (!(std::abs(det) > 1e-12 * scale)) return false;
  // Solve 2 u_i . x = |u_i|^2 (x: the centre relative to p0) by Cramer's rule in vector form.
  const glm::dvec3 offset = (glm::dot(u1, u1) * glm::cross(u2, u3) + glm::dot(u2, u2) * glm::cross(u3, u1) +
                             glm::dot(u3, u3) * glm::cross(u1, u2)) /
                            (2.0 * det);
  b->center = p0 + offset;
  b->radius = glm::length(offset);
  return true;
}

// The ball through a support set: the smallest with every support point on its boundary. A support that
// rounding made degenerate gets the smallest ball of its points instead, which still holds them all.
Ball support_ball(const glm::dvec3* s, int n) {
  Ball b;
  switch (n) {
    case 0:
      return b;
    case 1:
      b.center = s[0];
      b.radius = 0.0;
      return b;
    case 2:
      return diametral(s[0], s[1]);
    case 3:
      if (circumball(s[0], s[1], s[2], &b)) return b;
      return minimal_ball_of_few(s, 3);
    default:
      if (circumball(s[0], s[1], s[2], s[3], &b)) return b;
      return minimal_ball_of_few(s, 4);
  }
}

// Welzl's recursion with move-to-front: the smallest ball of points[0, end) with the support on its
// boundary. A point outside the current ball must lie on the boundary of the smallest ball of the points so
// far: it joins the support, the ball is recomputed over the points before it, and it moves to the front of
// the list (points that were outside once tend to be outside again: the support is found early). The
// support grows by one per level, so the recursion is at most four deep.
Ball welzl(std::vector<glm::dvec3>& points, size_t end, glm::dvec3* support, int n_support) {
  Ball b = support_ball(support, n_support);
  if (n_support == 4) return b;
  for (size_t i = 0; i < end; ++i) {
    if (holds(b, points[i])) continue;
    support[n_support] = points[i];
    b = welzl(points, i, support, n_support + 1);
    std::rotate(points.begin(), points.begin() + i, points.begin() + i + 1);  // move to front
  }
  return b;
}

}  // namespace

Ball minimal_ball_of_few(const glm::dvec3* p, int n) {
  Ball best;
  if (n <= 0) return best;
  auto consider = [&](const Ball& b) {
    if ((best.radius < 0.0 || b.radius < best.radius) && holds_all(b, p, n)) best = b;
  };
  Ball single;
  single.center = p[0];
  single.radius = 0.0;
  consider(single);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) consider(diametral(p[i], p[j]));
  Ball b;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        if (circumball(p[i], p[j], p[k], &b)) consider(b);
  if (n == 4 && circumball(p[0], p[1], p[2], p[3], &b)) consider(b);
  if (best.radius < 0.0) {
    // Only rounding can leave every candidate a hair short: take the widest pair and grow it.
    best = single;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) {
        Ball d = diametral(p[i], p[j]);
        if (d.radius > best.radius) best = d;
      }
    for (int i = 0; i < n; ++i) best.radius = std::max(best.radius, glm::distance(p[i], best.center));
  }
  return best;
}

Ball minimal_ball(std::vector<glm::dvec3> points, uint64_t seed) {
  if (points.empty()) return Ball{};
  // Work relative to the points' box centre: coordinates far from the origin keep their precision.
  glm::dvec3 lo = points[0], hi = points[0];
  for (const glm::dvec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 origin = 0.5 * (lo + hi);
  for (glm::dvec3& p : points) p -= origin;
  // Welzl's expected linear time needs a random order; a fixed seed makes the ball reproducible.
  std::mt19937_64 rng(seed);
  std::shuffle(points.begin(), points.end(), rng);
  glm::dvec3 support[4];
  Ball b = welzl(points, points.size(), support, 0);
  b.center += origin;
  return b;
}

Sphere bounding_sphere(const std::vector<glm::vec3>& points, const std::vector<Sphere>& spheres) {
  std::vector<glm::dvec3> pts;
  pts.reserve(points.size() + 6 * spheres.size());
  for (const glm::vec3& p : points) pts.emplace_back(p);
  for (const Sphere& s : spheres) {
    // A sphere's six extreme points: their minimal ball is the sphere itself (one sphere primitive gets
    // its own sphere back), and together with other points a ball close to the smallest.
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 e(0.0);
      e[a] = s.radius;
      pts.push_back(glm::dvec3(s.center) + e);
      pts.push_back(glm::dvec3(s.center) - e);
    }
  }
  Sphere out;
  if (pts.empty()) {
    out.radius = -1.f;
    return out;
  }
  const Ball b = minimal_ball(pts);
  out.center = glm::vec3(b.center);
  // The radius from the float centre, in double: each distance within gamma(3) of exact (float inputs, whose
  // differences double holds to an ulp); then grown by gamma(4) and rounded up to float.
  const glm::dvec3 c(out.center);
  double r = 0.0;
  for (const glm::vec3& p : points) r = std::max(r, glm::distance(glm::dvec3(p), c));
  for (const Sphere& s : spheres) r = std::max(r, glm::distance(glm::dvec3(s.center), c) + double(s.radius));
  r *= 1.0 + gamma_double(4);
  out.radius = float(r);
  if (double(out.radius) < r) out.radius = next_float_up(out.radius);
  return out;
}

}  // namespace raystep
