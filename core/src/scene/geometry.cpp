#include "raystep/scene/geometry.h"

namespace raystep {

uint32_t Geometry::begin_object(const std::string& name, uint32_t material) {
  Object o;
  o.name = name;
  o.first_prim = uint32_t(type_.size());
  o.material = material;
  objects_.push_back(o);
  return uint32_t(objects_.size() - 1);
}

static void ensure_object(std::vector<Object>& objects) {
  if (objects.empty()) objects.push_back(Object{"default", 0, 0, 0, Bounds3()});
}

uint32_t Geometry::add_triangle(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  ensure_object(objects_);
  uint32_t id = uint32_t(type_.size());
  type_.push_back(PrimType::triangle);
  local_.push_back(uint32_t(tri_verts_.size() / 3));
  object_.push_back(uint32_t(objects_.size() - 1));
  tri_verts_.insert(tri_verts_.end(), {p0, p1, p2});
  tri_has_normals_.push_back(0);
  if (!tri_normals_.empty()) tri_normals_.insert(tri_normals_.end(), 3, glm::vec3(0.f));
  Bounds3 b(p0, p1);
  b.extend(p2);
  objects_.back().prim_count++;
  objects_.back().bounds.extend(b);
  bounds_.extend(b);
  return id;
}

uint32_t Geometry::add_sphere(const Sphere& s) {
  ensure_object(objects_);
  uint32_t id = uint32_t(type_.size());
  type_.push_back(PrimType::sphere);
  local_.push_back(uint32_t(spheres_.size()));
  object_.push_back(uint32_t(objects_.size() - 1));
  spheres_.push_back(s);
  Bounds3 b = prim_bounds(id);
  objects_.back().prim_count++;
  objects_.back().bounds.extend(b);
  bounds_.extend(b);
  return id;
}

void Geometry::set_vertex_normals(uint32_t prim, const glm::vec3& n0, const glm::vec3& n1, const glm::vec3& n2) {
  uint32_t t = local_[prim];
  if (tri_normals_.empty()) tri_normals_.assign(tri_verts_.size(), glm::vec3(0.f));
  tri_normals_[3 * t] = n0;
  tri_normals_[3 * t + 1] = n1;
  tri_normals_[3 * t + 2] = n2;
  tri_has_normals_[t] = 1;
}

bool Geometry::has_vertex_normals(uint32_t id) const {
  return type_[id] == PrimType::triangle && !tri_normals_.empty() && tri_has_normals_[local_[id]];
}

Bounds3 Geometry::prim_bounds(uint32_t id) const {
  if (type_[id] == PrimType::triangle) {
    const glm::vec3* v = &tri_verts_[3 * local_[id]];
    Bounds3 b(v[0], v[1]);
    b.extend(v[2]);
    return b;
  }
  // Rounded outwards so that the box contains the whole sphere despite float rounding, and only where
  // rounding happened: an exact face stays exact (a sphere on the floor y = 0 would otherwise reach y =
  // -1.4e-45, and the SAH would cut that zero-width slab off every node above the floor).
  const Sphere& s = spheres_[local_[id]];
  glm::vec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = sub_round_down(s.center[a], s.radius);
    hi[a] = add_round_up(s.center[a], s.radius);
  }
  return Bounds3(lo, hi);
}

uint32_t add_to_geometry(const IndexedMesh& mesh, Geometry& g, const std::string& name, uint32_t material) {
  uint32_t object = g.begin_object(name, material);
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    g.add_triangle(mesh.vertex(i, 0), mesh.vertex(i, 1), mesh.vertex(i, 2));
  return object;
}

}  // namespace raystep
