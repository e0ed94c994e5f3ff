#include "raystep/geometry/prism.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "raystep/geometry/numerics.h"

namespace raystep {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Prism make_prism(int sides, double length, double radius, const glm::dvec3& center, const glm::dvec3& axis) {
  if (sides < 3 || sides > 64 || !(length > 0.0) || !(radius > 0.0) || !(glm::dot(axis, axis) > 0.0))
    throw std::invalid_argument("make_prism: 3..64 sides, positive length and radius, a nonzero axis");
  Prism p;
  p.sides = sides;
  p.length = length;
  p.radius = radius;
  p.center = center;
  p.axis = glm::normalize(axis);
  glm::dvec3 helper = std::fabs(p.axis.z) < 0.9 ? glm::dvec3(0.0, 0.0, 1.0) : glm::dvec3(1.0, 0.0, 0.0);
  p.u = glm::normalize(glm::cross(p.axis, helper));
  p.v = glm::cross(p.axis, p.u);
  // Vertices 0..sides-1 at the low end, sides..2 sides-1 at the high end.
  for (int end = 0; end < 2; ++end)
    for (int i = 0; i < sides; ++i) {
      double angle = 2.0 * kPi * i / sides;
      glm::dvec3 across = radius * (std::cos(angle) * p.u + std::sin(angle) * p.v);
      p.positions.push_back(glm::vec3(center + (end ? 0.5 : -0.5) * length * p.axis + across));
    }
  auto lo = [](int i) { return uint32_t(i); };
  auto hi = [&](int i) { return uint32_t(sides + i); };
  for (int i = 0; i < sides; ++i) {  // the long sides
    int j = (i + 1) % sides;
    p.triangles.emplace_back(lo(i), lo(j), hi(j));
    p.triangles.emplace_back(lo(i), hi(j), hi(i));
  }
  for (int i = 1; i + 1 < sides; ++i) {  // the end fans
    p.triangles.emplace_back(lo(0), lo(i + 1), lo(i));
    p.triangles.emplace_back(hi(0), hi(i), hi(i + 1));
  }
  return p;
}

std::vector<Ray> rays_inside(const Prism& p, size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double inner = p.radius * std::cos(kPi / p.sides);
  std::vector<Ray> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    glm::dvec3 d(u(rng), u(rng), u(rng));
    double len2 = glm::dot(d, d);
    if (len2 > 1.0 || len2 < 1e-4) continue;  // uniform directions: inside the unit ball, away from 0
    Ray r;
    r.origin = glm::vec3(p.center + 0.45 * p.length * u(rng) * p.axis +
                         0.25 * inner * (u(rng) * p.u + u(rng) * p.v));
    r.direction = glm::vec3(d / std::sqrt(len2));
    r.tmin = 0.f;
    r.tmax = kInfinity;
    rays.push_back(r);
  }
  return rays;
}

}  // namespace raystep
