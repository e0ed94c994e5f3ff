// A closed triangle mesh approximating a sphere: the regular icosahedron, each triangle split into four at
// its edge midpoints `subdivisions` times, every vertex projected onto the sphere (Loop-style 1-to-4 split).
// Vertices are shared by index, so neighbouring triangles use bit-identical edges: the test mesh for
// watertightness (every edge has exactly two triangles; V - E + F = 2).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace raystep {

class Geometry;

// An indexed mesh: triangles index into positions; all triangles wound counter-clockwise seen from outside.
struct Icosphere {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;

  glm::vec3 vertex(size_t tri, int k) const { return positions[triangles[tri][k]]; }
};

// 20 * 4^subdivisions triangles and 10 * 4^subdivisions + 2 vertices. subdivisions must be in [0, 8]
// (std::invalid_argument otherwise: a programming error, not user input).
Icosphere make_icosphere(int subdivisions, const glm::vec3& centre = glm::vec3(0.f), float radius = 1.f);

// Adds the mesh's triangles to g as one object; returns the object index.
uint32_t add_to_geometry(const Icosphere& mesh, Geometry& g, const std::string& name = "icosphere",
                         uint32_t material = 0);

}  // namespace raystep
