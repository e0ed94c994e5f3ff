// Triangle-box overlap by the separating axis theorem (Akenine-Moeller, "Fast 3D Triangle-Box Overlap
// Testing", JGT 2001): 13 candidate axes (3 box normals, the triangle normal, 9 edge cross products).
// Evaluated in double on a box enlarged by a relative margin and by a bound on the rounding of each projection,
// and every axis (the rounded triangle normal too) gets all three vertices projected, so the test is
// conservative: a triangle that touches the box is never rejected. Used to place a primitive in every grid cell
// it overlaps.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"

namespace raystep {

inline bool triangle_overlaps_box(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                  const Bounds3& box) {
  glm::dvec3 c = 0.5 * (glm::dvec3(box.lo) + glm::dvec3(box.hi));
  glm::dvec3 h = 0.5 * (glm::dvec3(box.hi) - glm::dvec3(box.lo));
  // Relative margin (about 2^-20 of the box's size and position): covers float rounding of the inputs.
  const double margin = 1.0 / (1 << 20);
  h += margin * (h + glm::abs(c));

  // Translate so that the box is centred at the origin.
  glm::dvec3 v[3] = {glm::dvec3(p0) - c, glm::dvec3(p1) - c, glm::dvec3(p2) - c};
  glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  // Separation along any axis w proves a miss, whether w is exact or rounded, provided the projections are
  // bounded: v_i is rounded once and w . v_i adds gamma(3), so |w . v_i - exact| <= gamma_double(4) |w| . m, m
  // the largest |v_i| per axis. gamma_double(8) (h + m) added to h covers that and the rounding of the radius
  // |w| . h itself: a huge triangle through a small box (size ratio 1e10) was rejected without it.
  glm::dvec3 m = glm::max(glm::abs(v[0]), glm::max(glm::abs(v[1]), glm::abs(v[2])));
  h += gamma_double(8) * (h + m);

  // 1. The box's face normals: the triangle's bounds against the box.
  for (int a = 0; a < 3; ++a) {
    double lo = std::min({v[0][a], v[1][a], v[2][a]}), hi = std::max({v[0][a], v[1][a], v[2][a]});
    if (lo > h[a] || hi < -h[a]) return false;
  }
  // 2. The nine cross products of triangle edges with the box axes.
  for (int i = 0; i < 3; ++i) {
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 axis(0.0);
      axis[(a + 1) % 3] = -e[i][(a + 2) % 3];
      axis[(a + 2) % 3] = e[i][(a + 1) % 3];  // axis = unit_a x e_i
      double d0 = glm::dot(v[0], axis), d1 = glm::dot(v[1], axis), d2 = glm::dot(v[2], axis);
      double rad = h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
      if (std::min({d0, d1, d2}) > rad || std::max({d0, d1, d2}) < -rad) return false;
    }
  }
  // 3. The triangle's normal against the box. For a sliver the rounded cross product is not quite normal to the
  // triangle, whose projection is then an interval, not one point: all three vertices are projected.
  glm::dvec3 n = glm::cross(e[0], e[1]);
  double d0 = glm::dot(n, v[0]), d1 = glm::dot(n, v[1]), d2 = glm::dot(n, v[2]);
  double rad = h.x * std::fabs(n.x) + h.y * std::fabs(n.y) + h.z * std::fabs(n.z);
  return std::min({d0, d1, d2}) <= rad && std::max({d0, d1, d2}) >= -rad;  // false for NaN vertices
}

// Sphere-box overlap: the squared distance from the centre to the box against r^2, with the same margin.
inline bool sphere_overlaps_box(const glm::vec3& center, float radius, const Bounds3& box) {
  double dist2 = 0.0;
  const double margin = 1.0 / (1 << 20);
  for (int a = 0; a < 3; ++a) {
    double lo = box.lo[a], hi = box.hi[a], x = center[a];
    double pad = margin * (std::fabs(lo) + std::fabs(hi) + (hi - lo));
    double gap = x < lo - pad ? lo - pad - x : (x > hi + pad ? x - hi - pad : 0.0);
    dist2 += gap * gap;
  }
  double r = double(radius) * (1.0 + margin);
  return dist2 <= r * r;
}

}  // namespace raystep
