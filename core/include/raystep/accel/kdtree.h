// The kd-tree accelerator (lecture: "kd-tree traversal"): depth-first, front to back, with an explicit stack.
// At an inner node compute t* on the split plane; if the ray crosses only the near child go there, only the far
// child go there, otherwise Intersect(near, tmin, t*) and push (far, t*, tmax). Pop when a leaf ends; stop when
// the nearest hit lies before the popped node's tmin. After pbrt-v3's KdTreeAccel::Intersect, with mailboxes
// for primitives that several leaves reference. Built by kdtree_build.h (SAH or spatial median).
#pragma once

#include <cmath>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/kdtree_build.h"
#include "raystep/accel/mailbox.h"
#include "raystep/accel/recorded_walk.h"
#include "raystep/geometry/component.h"
#include "raystep/record/recorder.h"

namespace raystep {

class KdTree final : public RecordedWalk<KdTree, KdOptions> {
 public:
  explicit KdTree(KdOptions options = {}, bool mailboxes = true)
      : RecordedWalk(options), use_mailboxes_(mailboxes) {}
  std::string name() const override { return options_.builder == KdBuilder::median ? "kd-median" : "kd"; }
  void build(const Geometry& geometry) override;
  // The same build, telling a listener about every node (SAH inspection, streamed build events).
  void build(const Geometry& geometry, BuildListener& listener);
  // Nodes, primitive lists and the per-node build information the debugger shows (boxes, parents, costs).
  size_t memory_bytes() const override {
    return tree_.nodes.capacity() * sizeof(KdNode) + tree_.info.capacity() * sizeof(KdNodeInfo) +
           tree_.prim_index.capacity() * sizeof(uint32_t);
  }

  // The traversal kernel, instrumented through the recorder (see record/recorder.h).
  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  const KdTreeData& data() const { return tree_; }
  bool mailboxes() const { return use_mailboxes_; }

 private:
  bool use_mailboxes_;
  KdTreeData tree_;
  Mailboxes mailboxes_;
};

template <class Recorder>
bool KdTree::traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  // Clip the ray to the root's box: the walk covers [t_min, t_max].
  SlabRay slab(ray);
  float t_min, t_max;
  if (tree_.nodes.empty() || !intersect_slabs(tree_.bounds, slab, &t_min, &t_max)) {
    rec.ray_end(*hit);
    return false;
  }
  // Computed t values stray a few ulps from the exact plane distances, so a decision that skips a node is taken
  // only beyond a margin of 2^-12 of the largest t in the root's box: a node within it is visited, which costs a
  // little time and never a hit.
  const float margin = std::max(std::fabs(t_min), std::fabs(t_max)) * (1.f / 4096.f);

  // The stack of far children still to visit, with the part of the ray inside each.
  struct Entry {
    uint32_t node;
    int32_t depth;
    float t_min, t_max;
    bool in_plane;  // pushed by a ray lying in the split plane, with the whole interval
  };
  Entry stack[kKdMaxDepth + 1];
  int stack_size = 0;
  int in_plane_entries = 0;  // while one is on the stack, the entries are not ordered by t_min

  MailboxStamp mailbox = use_mailboxes_ ? mailboxes_.begin_ray() : MailboxStamp(0, nullptr);
  WatertightRay wray(ray);
  Hit nearest;
  float t_nearest = ray.tmax;
  float t_limit = ray.tmax;  // the primitive tests' bound: once there is a hit, just above it, so that ties are seen
  uint32_t node_id = 0;
  int32_t depth = 0;
  const KdNode* nodes = tree_.nodes.data();
  const uint32_t* prim_ids = tree_.prim_index.data();
  for (;;) {
    const KdNode& node = nodes[node_id];
    rec.node(TreeStep{int32_t(node_id), depth, t_min, t_max});

    if (!node.is_leaf()) {
      // Inner node: t* where the ray meets the split plane.
      int axis = node.axis();
      float o = component(ray.origin, axis), d = component(ray.direction, axis);
      // A multiplication by the reciprocal, not a division: t* is on the path from one node to the next.
      float t_split = (node.split - o) * component(slab.inv_dir, axis);

      // The near child is the side the ray is on before it crosses the plane: below it for a direction that
      // points up the axis. By the sign bit, so that a ray parallel to the plane (direction +0 or -0, t* = +-inf)
      // stays on its origin's side, and an origin on the plane goes to the side the ray moves into.
      bool below_first = !std::signbit(d);
      uint32_t below = node_id + 1, above = node.above_child();
      // The below child is the next node, likely in the same cache line; the above child may be far away, so
      // its load starts now, while the ray is compared with the plane. One level further down on the below
      // side the same holds: start loading the below child's above child, or, when the below child is a leaf,
      // its list of primitives. (A random ray's walk is a chain of dependent loads; these start them early.)
      __builtin_prefetch(&nodes[above]);
      const KdNode& below_node = nodes[below];
      if (!below_node.is_leaf())
        __builtin_prefetch(&nodes[below_node.above_child()]);
      else
        __builtin_prefetch(prim_ids + below_node.first_prim);
      uint32_t near_child = below_first ? below : above, far_child = below_first ? above : below;

      // Advance to the next child node, possibly push the other one.
      if (t_split > t_max + margin) {
        node_id = near_child;  // the ray leaves the node before it reaches the plane
      } else if (t_split < t_min - margin) {
        node_id = far_child;  // the ray crossed the plane before it entered the node
      } else if (std::isnan(t_split)) {
        // The ray lies in the split plane (0 * inf): it touches both children over the whole interval.
        rec.push(TreeStep{int32_t(far_child), depth + 1, t_min, t_max});
        stack[stack_size++] = Entry{far_child, depth + 1, t_min, t_max, true};
        ++in_plane_entries;
        node_id = near_child;
      } else {
        // Both: Intersect(near, t_min, t*) now, push (far, t*, t_max) for later.
        float t_star = std::min(std::max(t_split, t_min), t_max);
        rec.push(TreeStep{int32_t(far_child), depth + 1, t_star, t_max});
        stack[stack_size++] = Entry{far_child, depth + 1, t_star, t_max, false};
        node_id = near_child;
        t_max = t_star;
      }
      ++depth;
      continue;
    }

    // Leaf: test its primitives, skipping those already tested for this ray (mailbox).
    rec.leaf(TreeStep{int32_t(node_id), depth, t_min, t_max});
    const uint32_t* prims = prim_ids + node.first_prim;
    const uint32_t n = node.prim_count();
    // Ask for all of the leaf's primitives first, so that their cache misses overlap.
    for (uint32_t i = 0; i < n; ++i) geometry_->prefetch(prims[i]);
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t prim = prims[i];
      if (use_mailboxes_ && !mailbox.first_visit(prim)) {
        rec.mailbox_hit(prim);
        continue;
      }
      Hit candidate;
      bool found = geometry_->intersect(prim, ray, wray, t_limit, &candidate);
      rec.prim_test(prim, found, candidate.t);
      if (!found) continue;
      // A tie (the same t: coincident faces, a shared edge) goes to the lower primitive id, as in brute force, so
      // every structure reports the same hit.
      if (candidate.t == t_nearest && int32_t(prim) > nearest.prim) continue;
      nearest = candidate;
      t_nearest = candidate.t;
      t_limit = next_float_up(t_nearest);
      if (any_hit) break;
    }
    if (any_hit && nearest.found()) {
      rec.hit_accepted(uint32_t(nearest.prim), t_nearest, AcceptReason::any_hit);
      break;
    }

    // Pop the next far child; with an empty stack the walk is over. Stop when the nearest hit lies before the
    // popped node's t_min: the entries below it start later still, so no primitive of theirs can be nearer.
    // (Not so while an in-plane entry is on the stack: it spans the whole interval, so only the popped entry
    // is skipped.)
    bool more = false;
    AcceptReason reason = AcceptReason::structure_done;
    while (stack_size > 0) {
      const Entry& e = stack[--stack_size];
      in_plane_entries -= e.in_plane;
      rec.pop(TreeStep{int32_t(e.node), e.depth, e.t_min, e.t_max});
      if (nearest.found() && t_nearest < e.t_min - margin) {
        reason = AcceptReason::next_node_beyond;
        if (in_plane_entries == 0) break;
        continue;
      }
      node_id = e.node;
      depth = e.depth;
      t_min = e.t_min;
      t_max = e.t_max;
      more = true;
      break;
    }
    if (!more) {
      if (nearest.found()) rec.hit_accepted(uint32_t(nearest.prim), t_nearest, reason);
      break;
    }
  }
  *hit = nearest;
  rec.ray_end(*hit);
  return hit->found();
}

}  // namespace raystep
