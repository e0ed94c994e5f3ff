#include "raystep/geometry/indexed_mesh.h"

#include "raystep/scene/geometry.h"

namespace raystep {

uint32_t add_to_geometry(const IndexedMesh& mesh, Geometry& g, const std::string& name, uint32_t material) {
  uint32_t object = g.begin_object(name, material);
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    g.add_triangle(mesh.vertex(i, 0), mesh.vertex(i, 1), mesh.vertex(i, 2));
  return object;
}

}  // namespace raystep
