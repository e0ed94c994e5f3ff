// A closed triangle mesh approximating a sphere: the regular icosahedron, each triangle split into four at
// its edge midpoints `subdivisions` times, every vertex projected onto the sphere (Loop-style 1-to-4 split).
// Vertices are shared by index, so neighbouring triangles use bit-identical edges: the test mesh for
// watertightness (every edge has exactly two triangles; V - E + F = 2).
#pragma once

#include <glm/vec3.hpp>

#include "raystep/geometry/indexed_mesh.h"

namespace raystep {

// An indexed mesh: all triangles wound counter-clockwise seen from outside.
struct Icosphere : IndexedMesh {};

// 20 * 4^subdivisions triangles and 10 * 4^subdivisions + 2 vertices. subdivisions must be in [0, 8]
// (std::invalid_argument otherwise: a programming error, not user input).
Icosphere make_icosphere(int subdivisions, const glm::vec3& centre = glm::vec3(0.f), float radius = 1.f);

}  // namespace raystep
