// The binary BVH accelerator (lecture: "bounding volume hierarchies"): depth-first, front to back, with an
// explicit stack. At an inner node test both children's boxes; enter the nearer one hit and push the other
// with its t_near; a popped entry whose t_near lies beyond the nearest hit is skipped. No mailboxes: each
// primitive is in exactly one leaf, so no primitive is tested twice (the kd-tree needs them because it copies
// a primitive into every cell it overlaps). Built by bvh_build.h.
#pragma once

#include <algorithm>
#include <cmath>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/geometry/component.h"
#include "raystep/trace/recorder.h"

namespace raystep {

// How the nearer child is chosen.
enum class BvhOrder : uint8_t {
  entry_distance,  // the child with the smaller t_near first
  split_axis,      // by the sign of the ray's direction on the node's split axis (no comparison of t)
};

// The slab test of geometry/bounds.h (intersect_slabs) prepared once per ray for the many boxes of one walk:
// the near and far planes chosen by the direction's sign bits up front, the three slabs combined without
// early exits. The same float operations in the same order, so the same answers: conservative (never a miss
// where the exact segment meets the box), +0 and -0 alike, NaN rays miss, a parallel ray outside a slab
// misses.
struct BvhBoxRay {
  glm::vec3 origin, inv_dir;
  int near_hi[3];  // 1: the near plane is the box's upper one (negative direction, or -0)
  float tmin, tmax;
  bool valid;
  explicit BvhBoxRay(const SlabRay& r)
      : origin(r.origin), inv_dir(r.inv_dir), tmin(r.tmin), tmax(r.tmax), valid(r.valid) {
    for (int a = 0; a < 3; ++a) near_hi[a] = std::signbit(r.inv_dir[a]) ? 1 : 0;
  }
  bool hit(const Bounds3& b, float* t_enter, float* t_exit) const {
    const glm::vec3* planes = &b.lo;  // planes[0] = lo, planes[1] = hi
    float t0 = tmin, t1 = tmax;
    for (int a = 0; a < 3; ++a) {
      float t_near = (planes[near_hi[a]][a] - origin[a]) * inv_dir[a];
      float t_far = (planes[1 - near_hi[a]][a] - origin[a]) * inv_dir[a];
      t_near *= t_near > 0.f ? 1.f - 2.f * gamma(3) : 1.f + 2.f * gamma(3);
      t_far *= t_far > 0.f ? 1.f + 2.f * gamma(3) : 1.f - 2.f * gamma(3);
      t0 = t_near > t0 ? t_near : t0;
      t1 = t_far < t1 ? t_far : t1;
    }
    *t_enter = t0;
    *t_exit = t1;
    return t0 <= t1 && t0 != kInfinity;
  }
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
  // Nodes, their build information and the primitive ids.
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

template <class Recorder>
bool Bvh::traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  BvhBoxRay slab{SlabRay(ray)};  // the box tests' ray; its tmax shrinks to just beyond the nearest hit
  float t_min, t_max;
  const BvhNode* nodes = bvh_.nodes.data();
  if (bvh_.nodes.empty() || !slab.valid || !slab.hit(nodes[0].box, &t_min, &t_max)) {
    if (!bvh_.nodes.empty()) rec.box_test(BoxTest{-1, 0, 0, false, 0.f, 0.f});  // the root's box: a miss
    rec.ray_end(*hit);
    return false;
  }
  rec.box_test(BoxTest{-1, 0, 0, true, t_min, t_max});
  // A primitive's computed t may stray a few ulps below its box's (conservative) entry distance, so a box is
  // given up only when it starts beyond the nearest hit by a margin of 2^-12 of the largest t in the root's
  // box: a box within it is visited, which costs a little time and never a hit (as in kdtree.h).
  const float margin = std::max(std::fabs(t_min), std::fabs(t_max)) * (1.f / 4096.f);

  // The stack of children still to visit, with the distance at which the ray enters each.
  struct Entry {
    uint32_t node;
    int32_t depth;
    float t_near, t_far;
  };
  Entry stack[kBvhMaxDepth + 1];
  int stack_size = 0;

  WatertightRay wray(ray);
  Hit nearest;
  float t_nearest = ray.tmax;
  float t_limit =
      ray.tmax;  // the primitive tests' bound: once there is a hit, just above it, so that ties are seen
  const uint32_t* prim_ids = bvh_.prim_index.data();
  uint32_t node_id = 0;
  int32_t depth = 0;
  for (;;) {
    const BvhNode& node = nodes[node_id];
    rec.node(TreeStep{int32_t(node_id), depth, t_min, t_max});

    if (!node.is_leaf()) {
      // Inner node: test both children's boxes (they may overlap: both may be entered).
      uint32_t left = node_id + 1, right = node.second_child();
      __builtin_prefetch(&nodes[right]);
      float l_near, l_far, r_near, r_far;
      bool hit_left = slab.hit(nodes[left].box, &l_near, &l_far);
      bool hit_right = slab.hit(nodes[right].box, &r_near, &r_far);
      rec.box_test(BoxTest{int32_t(node_id), int32_t(left), depth + 1, hit_left, l_near, l_far});
      rec.box_test(BoxTest{int32_t(node_id), int32_t(right), depth + 1, hit_right, r_near, r_far});
      if (hit_left && hit_right) {
        // Front to back: the nearer child now, the other on the stack with its entry distance.
        bool right_first = order_ == BvhOrder::entry_distance
                               ? r_near < l_near
                               : std::signbit(component(ray.direction, node.axis()));
        Entry far =
            right_first ? Entry{left, depth + 1, l_near, l_far} : Entry{right, depth + 1, r_near, r_far};
        rec.push(TreeStep{int32_t(far.node), far.depth, far.t_near, far.t_far});
        stack[stack_size++] = far;
        node_id = right_first ? right : left;
        t_min = right_first ? r_near : l_near;
        t_max = right_first ? r_far : l_far;
        ++depth;
        continue;
      }
      if (hit_left || hit_right) {
        node_id = hit_left ? left : right;
        t_min = hit_left ? l_near : r_near;
        t_max = hit_left ? l_far : r_far;
        ++depth;
        continue;
      }
    } else {
      // Leaf: test its primitives.
      rec.leaf(TreeStep{int32_t(node_id), depth, t_min, t_max});
      const uint32_t* prims = prim_ids + node.first_prim();
      const uint32_t n = node.prim_count();
      for (uint32_t i = 0; i < n; ++i) geometry_->prefetch(prims[i]);
      for (uint32_t i = 0; i < n; ++i) {
        uint32_t prim = prims[i];
        Hit candidate;
        bool found = geometry_->intersect(prim, ray, wray, t_limit, &candidate);
        rec.prim_test(prim, found, candidate.t);
        if (!found) continue;
        // A tie (the same t: coincident faces, a shared edge) goes to the lower primitive id, as in brute
        // force.
        if (candidate.t == t_nearest && int32_t(prim) > nearest.prim) continue;
        nearest = candidate;
        t_nearest = candidate.t;
        t_limit = next_float_up(t_nearest);
        // Boxes that start beyond the hit (and its margin) are misses from now on.
        slab.tmax = std::min(slab.tmax, t_nearest + margin);
        if (any_hit) break;
      }
      if (any_hit && nearest.found()) {
        rec.hit_accepted(uint32_t(nearest.prim), t_nearest, AcceptReason::any_hit);
        break;
      }
    }

    // Pop the next child; skip those that start beyond the nearest hit. The stack is not ordered by entry
    // distance (boxes overlap), so a skipped entry does not end the walk.
    bool more = false;
    while (stack_size > 0) {
      const Entry e = stack[--stack_size];
      rec.pop(TreeStep{int32_t(e.node), e.depth, e.t_near, e.t_far});
      if (nearest.found() && e.t_near > t_nearest + margin) {
        rec.skip(TreeStep{int32_t(e.node), e.depth, e.t_near, e.t_far});
        continue;
      }
      node_id = e.node;
      depth = e.depth;
      t_min = e.t_near;
      t_max = e.t_far;
      more = true;
      break;
    }
    if (!more) {
      if (nearest.found()) rec.hit_accepted(uint32_t(nearest.prim), t_nearest, AcceptReason::structure_done);
      break;
    }
  }
  *hit = nearest;
  rec.ray_end(*hit);
  return hit->found();
}

}  // namespace raystep
