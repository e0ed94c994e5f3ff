#include "raystep/scene/triangle_mesh.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace raystep {

Bounds3 TriangleMesh::bounds() const {
  Bounds3 b;
  for (const glm::uvec3& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  return b;
}

void add_mesh(Geometry& g, const TriangleMesh& mesh, const glm::mat4& transform) {
  const glm::mat3 linear(transform);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
  const bool mirrored = glm::determinant(linear) < 0.f;
  bool normals_ok = true;  // a singular transform has no normal matrix: then keep no vertex normals
  for (int c = 0; c < 3; ++c) normals_ok &= is_finite(normal_matrix[c]);

  auto place = [&](uint32_t i) { return glm::vec3(transform * glm::vec4(mesh.positions[i], 1.f)); };
  auto place_normal = [&](uint32_t i) {
    glm::vec3 n = normal_matrix * mesh.normals[i];
    float len = glm::length(n);
    return len > 0.f ? n / len : n;
  };
  const int second = mirrored ? 2 : 1, third = mirrored ? 1 : 2;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    uint32_t id = g.add_triangle(place(tri[0]), place(tri[second]), place(tri[third]));
    if (!normals_ok || mesh.normal_triangles.empty() || mesh.normal_triangles[t][0] == kNoNormal) continue;
    const glm::uvec3& nt = mesh.normal_triangles[t];
    g.set_vertex_normals(id, place_normal(nt[0]), place_normal(nt[second]), place_normal(nt[third]));
  }
}

TriangleMesh make_triangle(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2) {
  TriangleMesh m;
  m.positions = {v0, v1, v2};
  m.triangles = {{0, 1, 2}};
  return m;
}

TriangleMesh make_quad(const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2, const glm::vec3& v3) {
  TriangleMesh m;
  m.positions = {v0, v1, v2, v3};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TriangleMesh make_box(const glm::vec3& lo, const glm::vec3& hi) {
  // Corner i has x from bit 0, y from bit 1, z from bit 2 (0: lo, 1: hi).
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  // Each face as a quad wound counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z.
  const glm::uvec4 faces[6] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                               {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const glm::uvec4& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  return m;
}

}  // namespace raystep
