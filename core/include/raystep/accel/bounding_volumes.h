// The lecture's first speed-up: a bounding volume around each object; a ray that misses the volume skips all
// of the object's primitives. Objects are tested nearest volume first, and a volume entered beyond the
// nearest hit so far is skipped. "Many different kinds of bounding volumes": the axis-aligned box (bvol), the
// minimal sphere (bvol-sphere), the 14-DOP of 7 slab pairs (bvol-kdop) and the oriented box (bvol-obb) trade
// the cost of a volume test against how tightly the volume fits, so how often it lets a ray through in vain.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/geometry/dop.h"

namespace raystep {

enum class BvolKind : uint8_t {
  box,     // axis-aligned bounding box: 3 slab pairs (Kay and Kajiya), the default
  sphere,  // the smallest enclosing sphere (Welzl): one distance to the line; loose around long or flat
           // objects
  kdop,    // 14-DOP: slab pairs along the 3 axes and the 4 body diagonals, cutting the box's corners
  obb,     // oriented box: 3 slab pairs along the object's principal axes (PCA of its points)
};

// "bvol", "bvol-sphere", "bvol-kdop", "bvol-obb": accelerator names, so that the kinds compose with every
// --accel list and `raystep compare`.
const std::vector<std::string>& bvol_kind_names();
std::optional<BvolKind> parse_bvol_kind(const std::string& accel_name);  // nullopt: not a bvol name

// An oriented box: lo_k <= axes[k] . p <= hi_k.
struct OrientedBox {
  std::array<glm::dvec3, 3> axes;
  std::array<double, 3> lo, hi;
};

class BoundingVolumes final : public Accelerator {
 public:
  explicit BoundingVolumes(BvolKind kind = BvolKind::box) : kind_(kind) {}
  std::string name() const override { return bvol_kind_names()[size_t(kind_)]; }
  BvolKind kind() const { return kind_; }
  void build(const Geometry& geometry) override;
  bool intersect(const Ray& ray, Hit* hit) const override;
  bool occluded(const Ray& ray) const override;
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override;
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override;
  size_t memory_bytes() const override;

  // The volume test of one object, as the walk does it: [*t_enter, *t_exit] holds the part of the ray's
  // interval inside the volume. For tests and reports (the walk prepares the ray once for all objects).
  bool volume_hit(uint32_t object, const Ray& ray, float* t_enter = nullptr, float* t_exit = nullptr) const;

  // The built volumes of the current kind (the others are empty).
  const std::vector<Bounds3>& boxes() const { return boxes_; }
  const std::vector<Sphere>& spheres() const { return spheres_; }
  const std::vector<std::array<double, 14>>& kdops() const { return kdops_; }  // lo, hi per direction
  const std::vector<OrientedBox>& oriented_boxes() const { return obbs_; }

 private:
  struct VolumeRay;
  template <BvolKind K>
  bool enter(uint32_t object, const VolumeRay& vray, float* t_enter, float* t_exit) const;
  template <BvolKind K, class Recorder>
  bool walk(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;
  template <class Recorder>
  bool walk_kind(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  BvolKind kind_;
  const Geometry* geometry_ = nullptr;
  std::vector<Bounds3> boxes_;   // one per object (box)
  std::vector<Sphere> spheres_;  // one per object (sphere); radius < 0: an object without primitives
  std::vector<std::array<double, 14>> kdops_;  // one per object (kdop)
  std::vector<OrientedBox> obbs_;              // one per object (obb)
};

}  // namespace raystep
