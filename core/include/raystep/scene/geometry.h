// The scene's primitives in one id space. Primitive id = position in this list: objects in the order the
// scene lists them, each contributing its primitives in order (for an OBJ mesh: the 0-based order of the
// triangles in the file, a polygon v0..vn split as the fan (v0, vi, vi+1)). Every accelerator reports these
// ids.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/indexed_mesh.h"
#include "raystep/geometry/ray.h"
#include "raystep/geometry/sphere.h"
#include "raystep/geometry/split_space.h"
#include "raystep/geometry/triangle.h"

namespace raystep {

enum class PrimType : uint8_t { triangle, sphere };

// The nearest hit an accelerator reports: primitive id (-1: miss), t, and barycentrics b1, b2 of
// p = (1 - b1 - b2) p0 + b1 p1 + b2 p2 (zero for spheres).
struct Hit {
  int32_t prim = -1;
  float t = kInfinity;
  float b1 = 0.f, b2 = 0.f;
  bool found() const { return prim >= 0; }
};

// One object of the scene (a mesh, a sphere, a box...): a contiguous range of primitive ids.
struct Object {
  std::string name;  // e.g. "mesh bunny.obj", "sphere", "box"
  uint32_t first_prim = 0;
  uint32_t prim_count = 0;
  uint32_t material = 0;
  Bounds3 bounds;
};

class Geometry {
 public:
  // Building (used by the scene loader and by tests).
  uint32_t begin_object(const std::string& name, uint32_t material);  // returns the object index
  uint32_t add_triangle(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);  // returns id
  uint32_t add_sphere(const Sphere& s);
  // Optional smooth-shading normals of a triangle primitive (one per vertex).
  void set_vertex_normals(uint32_t prim, const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& n2);

  size_t size() const { return type_.size(); }
  PrimType type(uint32_t id) const { return type_[id]; }
  uint32_t material(uint32_t id) const { return objects_[object_[id]].material; }
  uint32_t object_of(uint32_t id) const { return object_[id]; }
  const std::vector<Object>& objects() const { return objects_; }
  const Bounds3& bounds() const { return bounds_; }
  Bounds3 prim_bounds(uint32_t id) const;
  bool all_triangles() const { return spheres_.empty(); }
  // Where the structures over it cut: in space, or in the plane for a flatland scene's walls
  // (geometry/split_space.h; set by add_flat_shapes).
  SplitSpace split_space() const { return space_; }
  void set_split_space(SplitSpace space) { space_ = space; }

  // Triangle vertices of a triangle primitive.
  const glm::vec3& vertex(uint32_t id, int k) const { return tri_verts_[3 * local_[id] + k]; }
  const Sphere& sphere(uint32_t id) const { return spheres_[local_[id]]; }
  bool has_vertex_normals(uint32_t id) const;
  glm::vec3 vertex_normal(uint32_t id, int k) const { return tri_normals_[3 * local_[id] + k]; }
  size_t triangle_count() const { return tri_verts_.size() / 3; }

  // Start loading a primitive's data (a triangle's 36 bytes of vertices may straddle two cache lines), so
  // that a leaf's primitives arrive together instead of one cache miss after another.
  void prefetch(uint32_t id) const {
    if (__builtin_expect(all_triangles(), 1)) {
      __builtin_prefetch(&tri_verts_[3 * id]);
      __builtin_prefetch(&tri_verts_[3 * id + 2]);
    }
  }

  // Test one primitive, with tmin < t < tmax. wray is the ray prepared for the watertight triangle test.
  // kInlineTriangle: the triangle test forced inline (triangle.h's intersect_triangle_inline).
  template <bool kInlineTriangle = false>
  [[gnu::always_inline]] bool intersect(uint32_t id, const Ray& ray, const WatertightRay& wray, float tmax, Hit* hit) const {
    // A scene of triangles only (every mesh) numbers its triangles like its primitives: the vertices are read
    // at once, without the type and local-index look-ups that stand between a primitive id and its data.
    const glm::vec3* v;
    if (__builtin_expect(all_triangles(), 1)) {
      v = &tri_verts_[3 * id];
    } else if (type_[id] == PrimType::triangle) {
      v = &tri_verts_[3 * local_[id]];
    } else {
      float t;
      if (!intersect_sphere(ray, spheres_[local_[id]], tmax, &t)) return false;
      hit->prim = int32_t(id);
      hit->t = t;
      hit->b1 = hit->b2 = 0.f;
      return true;
    }
    TriangleHit th;
    const bool found = kInlineTriangle ? intersect_triangle_inline(wray, v[0], v[1], v[2], tmax, &th)
                                       : intersect_triangle(wray, v[0], v[1], v[2], tmax, &th);
    if (!found) return false;
    hit->prim = int32_t(id);
    hit->t = th.t;
    hit->b1 = th.b1;
    hit->b2 = th.b2;
    return true;
  }

 private:
  std::vector<PrimType> type_;
  std::vector<uint32_t> local_;   // index into tri_verts_/3 or spheres_
  std::vector<uint32_t> object_;  // owning object
  std::vector<glm::vec3> tri_verts_;
  std::vector<glm::vec3> tri_normals_;    // 3 per triangle, or empty when no triangle has normals
  std::vector<uint8_t> tri_has_normals_;  // per triangle
  std::vector<Sphere> spheres_;
  std::vector<Object> objects_;
  Bounds3 bounds_;
  SplitSpace space_;
};

// Adds an indexed mesh's triangles (geometry/indexed_mesh.h) to g as one object; returns the object index.
uint32_t add_to_geometry(const IndexedMesh& mesh, Geometry& g, const std::string& name = "mesh",
                         uint32_t material = 0);

}  // namespace raystep
