// The binary BVH accelerator (lecture: "bounding volume hierarchies"): depth-first, front to back, with an
// explicit stack. At an inner node test both children's boxes; enter the nearer one hit and push the other
// with its t_near; a popped entry whose t_near lies beyond the nearest hit is skipped. No mailboxes: each
// primitive is in exactly one leaf, so no primitive is tested twice (the kd-tree needs them because it copies
// a primitive into every cell it overlaps). Built by bvh_build.h.
#pragma once

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/trace/recorder.h"

namespace raystep {

// How the nearer child is chosen.
enum class BvhOrder : uint8_t {
  entry_distance,  // the child with the smaller t_near first
  split_axis,      // by the sign of the ray's direction on the node's split axis (no comparison of t)
};

class Bvh final : public Accelerator {
 public:
  explicit Bvh(BvhOptions options = {}, BvhOrder order = BvhOrder::entry_distance)
      : options_(options), order_(order) {}
  // "bvh" (binned SAH), "bvh-sweep" or "bvh-median"
  std::string name() const override;
  void build(const Geometry& geometry) override;
  // The same build, telling a listener about every node (SAH inspection, tests).
  void build(const Geometry& geometry, BvhBuildListener& listener);
  bool intersect(const Ray& ray, Hit* hit) const override;
  bool occluded(const Ray& ray) const override;
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override;
  bool occluded_counted(const Ray& ray, CountingRecorder& counters) const override;
  size_t memory_bytes() const override;

  // The traversal kernel, instrumented through the recorder (trace/recorder.h): node, box_test, push, pop,
  // skip, leaf, prim_test, hit_accepted. Ties at equal t go to the lower primitive id, as in brute force.
  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  const BvhData& data() const { return bvh_; }
  const BvhOptions& options() const { return options_; }
  BvhOrder order() const { return order_; }
  const Geometry& geometry() const { return *geometry_; }

 private:
  BvhOptions options_;
  BvhOrder order_;
  const Geometry* geometry_ = nullptr;
  BvhData bvh_;
};

}  // namespace raystep
