// A closed thin prism: `sides` long rectangles (two triangles each, as long as the prism) around an axis,
// closed by a fan at each end. Long thin triangles seen from nearby are where a loose error bound once lost
// hits (29.6% of the rays from inside a 20 x 0.02 hexagonal prism leaked): the watertightness test mesh for
// slivers, as icosphere.h is for shared edges and vertices. Vertices are shared by index, computed in double,
// rounded once.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/indexed_mesh.h"
#include "raystep/geometry/ray.h"

namespace raystep {

struct Prism : IndexedMesh {
  int sides = 6;
  double length = 1.0, radius = 0.01;  // radius: of the circle through the long edges
  glm::dvec3 center{0.0}, axis{1.0, 0.0, 0.0}, u{0.0, 1.0, 0.0},
      v{0.0, 0.0, 1.0};  // u, v: unit, across the axis
  // positions: 2 * sides; triangles: 4 * sides - 4
};

// sides in [3, 64], length and radius > 0, axis nonzero (std::invalid_argument otherwise: a programming
// error).
Prism make_prism(int sides, double length, double radius, const glm::dvec3& center = glm::dvec3(0.0),
                 const glm::dvec3& axis = glm::dvec3(1.0, 0.0, 0.0));

// Rays from inside, near the axis (within a quarter of the inscribed radius, along 90% of the length), in
// uniformly random directions, tmin 0, tmax +inf: every one of them must hit the prism.
std::vector<Ray> rays_inside(const Prism& prism, size_t count, uint32_t seed);

}  // namespace raystep
