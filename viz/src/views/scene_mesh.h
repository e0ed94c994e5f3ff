// The 3D view's copy of a scene's geometry: every primitive as flat-coloured triangles (a sphere tessellated)
// in VTK's arrays, with each triangle's primitive id for picking. A scene's is made where the scene is
// loaded, on the loading worker: for a 2-million-triangle mesh that is a second of work the GUI thread would
// stall for.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"

class vtkPolyData;

namespace raystep {
class Geometry;
struct Scene;
struct Trace;
struct TracePrimitive;
}  // namespace raystep

namespace raystep::viz {

// A primitive as the 3D view draws it: a triangle's vertices, or a sphere's centre (v[0]) and radius.
struct PrimShape {
  bool sphere = false;
  glm::vec3 v[3]{};
  float radius = 0.f;
};
PrimShape shapeOf(const Geometry& g, uint32_t id);
PrimShape shapeOf(const TracePrimitive& p);

// The UV sphere the 3D view draws for a sphere primitive: kSphereSlices points on each of kSphereStacks + 1
// rings, pole to pole, and two triangles for each of the stacks x slices quads (indices into the points).
constexpr int kSphereSlices = 24, kSphereStacks = 14;
void sphereMesh(const glm::vec3& centre, float radius, std::vector<glm::vec3>* points,
                std::vector<int32_t>* triangles);

class SceneMesh {
 public:
  // The scene's primitives in their materials' colours (a mirror as grey-blue metal).
  static std::shared_ptr<const SceneMesh> fromScene(const Scene& scene);
  // The primitives a trace opened alone lists, in one grey.
  static std::shared_ptr<const SceneMesh> fromTrace(const Trace& trace);
  ~SceneMesh();

  // Points, triangles and a colour per triangle (cell data scalars). Read-only once made: views share it.
  vtkPolyData* data() const { return data_; }
  // The primitive id of each triangle of data() (a sphere is many triangles).
  const std::vector<int32_t>& cellPrim() const { return cellPrim_; }
  const Bounds3& bounds() const { return bounds_; }

 private:
  SceneMesh();
  vtkPolyData* data_;  // owned (one reference)
  std::vector<int32_t> cellPrim_;
  Bounds3 bounds_;
};

}  // namespace raystep::viz
