#include "raystep/geometry/icosphere.h"

#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>


namespace raystep {

Icosphere make_icosphere(int subdivisions, const glm::vec3& centre, float radius) {
  if (subdivisions < 0 || subdivisions > 8)
    throw std::invalid_argument("make_icosphere: subdivisions not in [0, 8]");
  // Unit directions in double until the very end, so that each vertex is rounded to float exactly once.
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;  // the golden ratio: (0, +-1, +-phi) and its cyclic shifts
  std::vector<glm::dvec3> dirs = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                  {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                  {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (glm::dvec3& d : dirs) d = glm::normalize(d);
  std::vector<glm::uvec3> tris = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                  {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                  {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                  {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};

  // Subdivision step: one new vertex per edge, shared by both triangles of the edge (keyed by the
  // unordered vertex pair), projected onto the unit sphere.
  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<uint64_t, uint32_t> midpoint;
    auto mid = [&](uint32_t i, uint32_t j) {
      uint64_t key = i < j ? (uint64_t(i) << 32 | j) : (uint64_t(j) << 32 | i);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      dirs.push_back(glm::normalize(dirs[i] + dirs[j]));
      uint32_t index = uint32_t(dirs.size() - 1);
      midpoint.emplace(key, index);
      return index;
    };
    std::vector<glm::uvec3> next;
    next.reserve(4 * tris.size());
    for (const glm::uvec3& t : tris) {
      uint32_t a = mid(t[0], t[1]), b = mid(t[1], t[2]), c = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], a, c}, {t[1], b, a}, {t[2], c, b}, {a, b, c}});
    }
    tris.swap(next);
  }

  Icosphere mesh;
  mesh.triangles = std::move(tris);
  mesh.positions.reserve(dirs.size());
  for (const glm::dvec3& d : dirs)
    mesh.positions.push_back(glm::vec3(glm::dvec3(centre) + double(radius) * d));
  return mesh;
}

}  // namespace raystep
