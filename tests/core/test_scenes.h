// Small generated scenes and the brute-force comparison shared by the structure tests (grid, kd-tree, traces).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

#include <vector>

#include <glm/geometric.hpp>

#include "raystep/accel/brute_force.h"
#include "raystep/scene/geometry.h"

namespace raystep::test {

// A soup of random small triangles and a few spheres in [-2, 2]^3.
inline Geometry make_soup(uint32_t seed, int triangles, int spheres) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.f, 2.f), s(-0.4f, 0.4f);
  g.begin_object("soup", 0);
  for (int i = 0; i < triangles; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    g.add_triangle(p, p + glm::vec3(s(rng), s(rng), s(rng)), p + glm::vec3(s(rng), s(rng), s(rng)));
  }
  for (int i = 0; i < spheres; ++i) g.add_sphere(Sphere{glm::vec3(u(rng), u(rng), u(rng)), 0.3f});
  return g;
}

// A closed thin prism: `sides` long sides (two triangles each, as long as the prism) around `axis` (unit), with
// circumradius `radius`, `length` long, centred at `center`, and fans closing both ends: the long thin triangles
// that a loose error bound loses. Vertices computed in double and rounded once.
struct Prism {
  glm::dvec3 center, axis, u, v;  // u, v: unit vectors across the axis
  double length, radius;
  int sides;
};
inline Prism make_prism_frame(int sides, double length, double radius, glm::dvec3 center, glm::dvec3 axis) {
  axis = glm::normalize(axis);
  glm::dvec3 helper = std::abs(axis.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  glm::dvec3 u = glm::normalize(glm::cross(axis, helper));
  return Prism{center, axis, u, glm::cross(axis, u), length, radius, sides};
}
inline void add_prism(Geometry& g, const Prism& p) {
  g.begin_object("prism", 0);
  std::vector<glm::vec3> lo, hi;
  for (int i = 0; i < p.sides; ++i) {
    double angle = 2.0 * 3.14159265358979323846 * i / p.sides;
    glm::dvec3 across = p.radius * (std::cos(angle) * p.u + std::sin(angle) * p.v);
    lo.push_back(glm::vec3(p.center - 0.5 * p.length * p.axis + across));
    hi.push_back(glm::vec3(p.center + 0.5 * p.length * p.axis + across));
  }
  for (int i = 0; i < p.sides; ++i) {
    int j = (i + 1) % p.sides;
    g.add_triangle(lo[i], hi[i], hi[j]);
    g.add_triangle(lo[i], hi[j], lo[j]);
  }
  for (int i = 1; i + 1 < p.sides; ++i) {
    g.add_triangle(lo[0], lo[i + 1], lo[i]);
    g.add_triangle(hi[0], hi[i], hi[i + 1]);
  }
}
// Rays from inside the prism near its axis (within a quarter of the inscribed radius, along 90% of its length),
// in uniformly random directions: every one must hit the prism.
inline std::vector<Ray> rays_inside_prism(const Prism& p, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double inner = p.radius * std::cos(3.14159265358979323846 / p.sides);
  std::vector<Ray> rays;
  while (int(rays.size()) < count) {
    glm::dvec3 d(u(rng), u(rng), u(rng));
    double len2 = glm::dot(d, d);
    if (len2 > 1.0 || len2 < 1e-4) continue;
    Ray r;
    r.origin = glm::vec3(p.center + 0.45 * p.length * u(rng) * p.axis + 0.25 * inner * (u(rng) * p.u + u(rng) * p.v));
    r.direction = glm::vec3(d / std::sqrt(len2));
    r.tmin = 0.f;
    r.tmax = kInfinity;
    rays.push_back(r);
  }
  return rays;
}

// Rays on which a structure's answer differs from brute force's: another primitive, another t, or another
// occlusion. Ties (coincident faces, a shared edge) go to the lower primitive id everywhere, so they count too.
inline int count_disagreements(const Accelerator& acc, const BruteForce& brute, const std::vector<Ray>& rays) {
  int bad = 0;
  for (const Ray& r : rays) {
    Hit a, b;
    bool ha = brute.intersect(r, &a), hb = acc.intersect(r, &b);
    if (ha != hb || a.prim != b.prim || a.t != b.t || brute.occluded(r) != acc.occluded(r)) ++bad;
  }
  return bad;
}

}  // namespace raystep::test
