// The binary BVH accelerator (lecture: "bounding volume hierarchies"): depth-first, front to back, with an
// explicit stack. At an inner node test both children's boxes; enter the nearer one hit and push the other
// with its t_near; a popped entry whose t_near lies beyond the nearest hit is skipped. No mailboxes: each
// primitive is in exactly one leaf, so no primitive is tested twice (the kd-tree needs them because it copies
// a primitive into every cell it overlaps). Built by bvh_build.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_box_ray.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/accel/bvh_pair.h"
#include "raystep/accel/recorded_walk.h"
#include "raystep/geometry/component.h"
#include "raystep/record/recorder.h"

namespace raystep {

// How the nearer child is chosen.
enum class BvhOrder : uint8_t {
  entry_distance,  // the child with the smaller t_near first
  split_axis,      // by the sign of the ray's direction on the node's split axis (no comparison of t)
};

class Bvh final : public RecordedWalk<Bvh, BvhOptions> {
 public:
  explicit Bvh(BvhOptions options = {}, BvhOrder order = BvhOrder::entry_distance)
      : RecordedWalk(options), order_(order) {}
  // "bvh" (binned SAH), "bvh-sweep", "bvh-median" or "bvh-sbvh" (bvh_names.h)
  std::string name() const override;
  void build(const Geometry& geometry) override;
  // The same build, telling a listener about every node (SAH inspection, tests).
  void build(const Geometry& geometry, BvhBuildListener& listener);
  // Nodes, their build information and the primitive ids.
  size_t memory_bytes() const override;

  // The traversal kernel, instrumented through the recorder (record/recorder.h): node, box_test, push, pop,
  // skip, leaf, prim_test, hit_accepted. Ties at equal t go to the lower primitive id, as in brute force.
  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  const BvhData& data() const { return bvh_; }
  const BvhPairs& pairs() const { return pairs_; }  // the walk's copy (bvh_pair.h)
  BvhOrder order() const { return order_; }

 private:
  BvhOrder order_;
  BvhData bvh_;
  BvhPairs pairs_;  // the walk's copy: each inner node's children side by side
};

template <class Recorder>
bool Bvh::traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  BvhBoxRay slab{SlabRay(ray)};         // the box tests' ray; its tmax shrinks to just beyond the nearest hit
  float t_root_near[2], t_root_far[2];  // the root's box, tested in both lanes of a pair (bvh_pair.h)
  if (bvh_.nodes.empty() || !slab.valid ||
      !(slab.hit_children(pairs_.root_box, t_root_near, t_root_far) & 1)) {
    if (!bvh_.nodes.empty()) rec.box_test(BoxTest{-1, 0, 0, false, 0.f, 0.f});  // the root's box: a miss
    rec.ray_end(*hit);
    return false;
  }
  float t_min = t_root_near[0], t_max = t_root_far[0];
  rec.box_test(BoxTest{-1, 0, 0, true, t_min, t_max});
  // A primitive's computed t may stray a few ulps below its box's (conservative) entry distance, so a box is
  // given up only when it starts beyond the nearest hit by a margin of 2^-12 of the largest t in the root's
  // box: a box within it is visited, which costs a little time and never a hit (as in kdtree.h).
  const float margin = std::max(std::fabs(t_min), std::fabs(t_max)) * (1.f / 4096.f);

  // The stack of children still to visit, with the distance at which the ray enters each (and, for traces,
  // the node's id and depth).
  struct Entry {
    BvhRef ref;
    float t_near, t_far;
    int32_t id, depth;
  };
  Entry stack[kBvhMaxDepth + 1];
  int stack_size = 0;

  std::optional<WatertightRay> wray;  // prepared at the first leaf: many rays reach none
  Hit nearest;
  float t_nearest = ray.tmax;
  float t_limit =
      ray.tmax;  // the primitive tests' bound: once there is a hit, just above it, so that ties are seen
  const BvhPair* pairs = pairs_.pairs.data();
  const uint32_t* prim_ids = bvh_.prim_index.data();
  BvhRef node = pairs_.root;
  int32_t node_id = 0, depth = 0;  // traces only
  for (;;) {
    rec.node(TreeStep{node_id, depth, t_min, t_max});

    if (!node.is_leaf()) {
      // Inner node: test both children's boxes (they may overlap: both may be entered).
      const BvhPair& pair = pairs[node.index];
      float t_near[2], t_far[2];
      const int hits = slab.hit_children(pair, t_near, t_far);
      int32_t child_id[2] = {0, 0};
      if constexpr (kReadsNodeIds<Recorder>) {
        child_id[0] = pairs_.child_id[2 * node.index];
        child_id[1] = pairs_.child_id[2 * node.index + 1];
      }
      rec.box_test(BoxTest{node_id, child_id[0], depth + 1, (hits & 1) != 0, t_near[0], t_far[0]});
      rec.box_test(BoxTest{node_id, child_id[1], depth + 1, (hits & 2) != 0, t_near[1], t_far[1]});
      if (hits != 0) {
        // One child hit: enter it. Both: front to back, the nearer now, the other on the stack with its
        // entry distance.
        int first = hits == 2 ? 1 : 0;
        if (hits == 3) {
          first = order_ == BvhOrder::entry_distance
                      ? (t_near[1] < t_near[0] ? 1 : 0)
                      : (std::signbit(component(ray.direction, pairs_.axis[node.index])) ? 1 : 0);
          const int other = 1 - first;
          Entry far{pair.child[other], t_near[other], t_far[other], child_id[other], depth + 1};
          rec.push(TreeStep{far.id, far.depth, far.t_near, far.t_far});
          stack[stack_size++] = far;
        }
        node = pair.child[first];
        node_id = child_id[first];
        t_min = t_near[first];
        t_max = t_far[first];
        ++depth;
        continue;
      }
    } else {
      // Leaf: test its primitives.
      rec.leaf(TreeStep{node_id, depth, t_min, t_max});
      if (!wray) wray.emplace(ray);
      const uint32_t* prims = prim_ids + node.index;
      const uint32_t n = node.count;
      for (uint32_t i = 0; i < n; ++i) geometry_->prefetch(prims[i]);
      for (uint32_t i = 0; i < n; ++i) {
        uint32_t prim = prims[i];
        Hit candidate;
        bool found = geometry_->intersect(prim, ray, *wray, t_limit, &candidate);
        rec.prim_test(prim, found, candidate.t);
        if (!found) continue;
        // A tie (the same t: coincident faces, a shared edge) goes to the lower primitive id, as in brute
        // force.
        if (candidate.t == t_nearest && int32_t(prim) > nearest.prim) continue;
        nearest = candidate;
        t_nearest = candidate.t;
        t_limit = next_float_up(t_nearest);
        // Boxes that start beyond the hit (and its margin) are misses from now on.
        slab.set_tmax(std::min(slab.tmax, t_nearest + margin));
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
      rec.pop(TreeStep{e.id, e.depth, e.t_near, e.t_far});
      if (nearest.found() && e.t_near > t_nearest + margin) {
        rec.skip(TreeStep{e.id, e.depth, e.t_near, e.t_far});
        continue;
      }
      node = e.ref;
      node_id = e.id;
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
