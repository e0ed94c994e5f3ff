// A copy of Bvh::traverse with every recorder hook removed, for the measurement that proves the null recorder
// costs nothing: the two must count the same instructions under callgrind (bench/bvh_instructions.cpp).
// Keep it in step with core/include/raystep/accel/bvh.h.
#pragma once

#include "raystep/accel/bvh.h"

namespace raystep::bench {

inline bool bvh_traverse_hookfree(const Bvh& bvh, const Ray& ray, Hit* hit, bool any_hit) {
  const BvhData& bvh_ = bvh.data();
  const Geometry* geometry_ = &bvh.geometry();
  const BvhOrder order_ = bvh.order();
  *hit = Hit{};
  BvhBoxRay slab{SlabRay(ray)};  // the box tests' ray; its tmax shrinks to just beyond the nearest hit
  float t_min, t_max;
  const BvhNode* nodes = bvh_.nodes.data();
  if (bvh_.nodes.empty() || !slab.valid || !slab.hit(nodes[0].box, &t_min, &t_max)) {
    return false;
  }
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

    if (!node.is_leaf()) {
      // Inner node: test both children's boxes (they may overlap: both may be entered).
      uint32_t left = node_id + 1, right = node.second_child();
      __builtin_prefetch(&nodes[right]);
      float l_near, l_far, r_near, r_far;
      bool hit_left = slab.hit(nodes[left].box, &l_near, &l_far);
      bool hit_right = slab.hit(nodes[right].box, &r_near, &r_far);
      if (hit_left && hit_right) {
        // Front to back: the nearer child now, the other on the stack with its entry distance.
        bool right_first = order_ == BvhOrder::entry_distance
                               ? r_near < l_near
                               : std::signbit(component(ray.direction, node.axis()));
        Entry far =
            right_first ? Entry{left, depth + 1, l_near, l_far} : Entry{right, depth + 1, r_near, r_far};
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
      const uint32_t* prims = prim_ids + node.first_prim();
      const uint32_t n = node.prim_count();
      for (uint32_t i = 0; i < n; ++i) geometry_->prefetch(prims[i]);
      for (uint32_t i = 0; i < n; ++i) {
        uint32_t prim = prims[i];
        Hit candidate;
        bool found = geometry_->intersect(prim, ray, wray, t_limit, &candidate);
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
      node_id = e.node;
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
