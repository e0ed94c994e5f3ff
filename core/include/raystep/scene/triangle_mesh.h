// An indexed triangle mesh as loaded from a file or built from a scene's shape (triangle, quad, box), and
// its placement in the scene's Geometry: vertices through the object's transform, normals through the
// inverse transpose. The triangles keep their order, which is their primitive id order.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "raystep/scene/geometry.h"

namespace raystep {

// normal_triangles[i] for a triangle without vertex normals.
constexpr uint32_t kNoNormal = 0xffffffffu;

struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;           // indices into positions
  std::vector<glm::vec3> normals;
  std::vector<glm::uvec3> normal_triangles;    // empty or parallel to triangles (indices into normals,
                                               // or all kNoNormal for a triangle without them)
  Bounds3 bounds() const;
};

// Appends the mesh's triangles to the current object of g, in order (the caller calls begin_object).
// p' = M p; n' = normalize(inverse transpose of M's 3x3 part times n). A mirroring transform (det < 0)
// would turn the winding inside out, so then each triangle is stored as (v0, v2, v1), which keeps the
// geometric normal (v1 - v0) x (v2 - v0) pointing the way the mesh's own winding said.
void add_mesh(Geometry& g, const TriangleMesh& mesh, const glm::mat4& transform);

// Shapes of the scene file as meshes.
TriangleMesh make_triangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2);
// Two triangles (v0, v1, v2), (v0, v2, v3).
TriangleMesh make_quad(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2, const glm::vec3& v3);
// An axis-aligned box: 12 triangles, two per face in the order -x, +x, -y, +y, -z, +z, each wound
// counter-clockwise seen from outside (geometric normal pointing out).
TriangleMesh make_box(const glm::vec3& lo, const glm::vec3& hi);

}  // namespace raystep
