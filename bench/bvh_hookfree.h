// A copy of Bvh::traverse with every recorder hook removed, for the measurement that proves the null recorder
// costs nothing: the two must count the same instructions under callgrind (bench/bvh_instructions.cpp).
// Keep it in step with core/include/raystep/accel/bvh.h.
#pragma once

#include "raystep/accel/bvh.h"

namespace raystep::bench {

// Not inlined, as the library's kernel is not: both pay the same call.
[[gnu::noinline]] inline bool bvh_traverse_hookfree(const Bvh& bvh, const Ray& ray, Hit* hit, bool any_hit) {
  const BvhData& bvh_ = bvh.data();
  const BvhPairs& pairs_ = bvh.pairs();
  const Geometry* geometry_ = &bvh.geometry();
  const BvhOrder order_ = bvh.order();
  *hit = Hit{};
  BvhBoxRay slab{SlabRay(ray)};         // the box tests' ray; its tmax shrinks to just beyond the nearest hit
  float t_root_near[2], t_root_far[2];  // the root's box, tested in both lanes of a pair (bvh_pair.h)
  if (bvh_.nodes.empty() || !slab.valid ||
      !(slab.hit_children(pairs_.root_box, t_root_near, t_root_far) & 1)) {
    return false;
  }
  float t_min = t_root_near[0], t_max = t_root_far[0];
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
    if (!node.is_leaf()) {
      // Inner node: test both children's boxes (they may overlap: both may be entered).
      const BvhPair& pair = pairs[node.index];
      float t_near[2], t_far[2];
      const int hits = slab.hit_children(pair, t_near, t_far);
      int32_t child_id[2] = {0, 0};
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
      if (!wray) wray.emplace(ray);
      const uint32_t* prims = prim_ids + node.index;
      const uint32_t n = node.count;
      for (uint32_t i = 0; i < n; ++i) geometry_->prefetch(prims[i]);
      for (uint32_t i = 0; i < n; ++i) {
        uint32_t prim = prims[i];
        Hit candidate;
        bool found = geometry_->intersect(prim, ray, *wray, t_limit, &candidate);
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
        break;
      }
    }

    // Pop the next child; skip those that start beyond the nearest hit. The stack is not ordered by entry
    // distance (boxes overlap), so a skipped entry does not end the walk.
    bool more = false;
    while (stack_size > 0) {
      const Entry e = stack[--stack_size];
      if (nearest.found() && e.t_near > t_nearest + margin) {
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
      break;
    }
  }
  *hit = nearest;
  return hit->found();
}

}  // namespace raystep::bench
