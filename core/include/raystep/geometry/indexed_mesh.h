// An indexed triangle mesh: triangles index into shared positions, so neighbouring triangles use
// bit-identical edges. The shape of the generated watertightness test meshes (icosphere.h, prism.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace raystep {

class Geometry;

struct IndexedMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;  // wound counter-clockwise seen from outside

  glm::vec3 vertex(size_t tri, int k) const { return positions[triangles[tri][k]]; }
};

// Adds the mesh's triangles to g as one object; returns the object index.
uint32_t add_to_geometry(const IndexedMesh& mesh, Geometry& g, const std::string& name = "mesh",
                         uint32_t material = 0);

}  // namespace raystep
