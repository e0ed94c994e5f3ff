// An indexed triangle mesh: triangles index into shared positions, so neighbouring triangles use
// bit-identical edges. The shape of the generated watertightness test meshes (icosphere.h, prism.h); scene/geometry.h adds one to a scene's primitives.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace raystep {

struct IndexedMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;  // wound counter-clockwise seen from outside

  glm::vec3 vertex(size_t tri, int k) const { return positions[triangles[tri][k]]; }
};

}  // namespace raystep
