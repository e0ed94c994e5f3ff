// The lecture's first speed-up: a bounding box around each object; a ray that misses the box skips all of
// the object's primitives. Objects are tested nearest box first, and a box entered beyond the nearest hit
// so far is skipped.
#pragma once

#include <vector>

#include "raystep/accel/accelerator.h"

namespace raystep {

class BoundingVolumes final : public Accelerator {
 public:
  std::string name() const override { return "bvol"; }
  void build(const Geometry& geometry) override;
  bool intersect(const Ray& ray, Hit* hit) const override;
  bool occluded(const Ray& ray) const override;
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override;
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override;
  size_t memory_bytes() const override { return boxes_.capacity() * sizeof(Bounds3); }

 private:
  template <class Recorder>
  bool walk(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  const Geometry* geometry_ = nullptr;
  std::vector<Bounds3> boxes_;  // one per object
};

}  // namespace raystep
