// The 3D view's copy of a scene's geometry: every primitive as flat-coloured triangles (a sphere tessellated)
// in VTK's arrays, with each triangle's primitive id for picking. A scene's is made where the scene is
// loaded, on the loading worker: for a 2-million-triangle mesh that is a second of work the GUI thread would
// stall for. Beyond kDisplayTriangles the view draws a decimated copy (VTK's quadric clustering, Lindstrom
// 2000): uploading and first drawing two million triangles blocks the GUI thread, which owns the OpenGL
// context, for over a second; picking then goes through the ray tracer (SceneView), so it finds the
// primitive the tracer sees, not the display copy's.
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
  // A decimated display copy: data() holds displayTriangles() of the scene's sceneTriangles(), and
  // cellPrim() gives each display triangle one of the primitives it stands for.
  bool decimated() const { return decimated_; }
  size_t displayTriangles() const;
  size_t sceneTriangles() const { return sceneTriangles_; }

 private:
  SceneMesh();
  void decimate();     // replaces data() by the display copy
  vtkPolyData* data_;  // owned (one reference)
  std::vector<int32_t> cellPrim_;
  Bounds3 bounds_;
  bool decimated_ = false;
  size_t sceneTriangles_ = 0;
};

// Above this many triangles the 3D view draws a decimated copy (about 0.6 us of GUI-thread upload and first
// drawing a triangle under llvmpipe: a quarter million is 0.15 s).
constexpr size_t kDisplayTriangles = 250000;

}  // namespace raystep::viz
