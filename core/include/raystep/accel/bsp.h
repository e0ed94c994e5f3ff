// The general BSP tree accelerator (lecture: "BSP tree traversal is the kd-tree's, with a general plane"):
// depth-first, front to back, with an explicit stack. At an inner node t* = (d - n.o) / (n.dir); if the ray
// crosses only the near child go there, only the far child go there, otherwise Intersect(near, tmin, t*) and
// push (far, t*, tmax). The price of the general plane is a dot product where the kd-tree reads one
// coordinate, and a t* that is only known to lie in an interval: the kernel computes it in double with a
// rigorous error bound and gives each child the whole interval it may need. Built by bsp_build.h.
#pragma once

#include <cmath>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bsp_build.h"
#include "raystep/accel/mailbox.h"
#include "raystep/accel/nearest_hit.h"
#include "raystep/accel/recorded_walk.h"
#include "raystep/record/recorder.h"

namespace raystep {

class BspTree final : public RecordedWalk<BspTree, BspOptions> {
 public:
  explicit BspTree(BspOptions options = {}, bool mailboxes = true)
      : RecordedWalk(options), use_mailboxes_(mailboxes) {}
  std::string name() const override { return "bsp"; }
  void build(const Geometry& geometry) override;
  size_t memory_bytes() const override {
    return tree_.nodes.capacity() * sizeof(BspNode) + tree_.info.capacity() * sizeof(BspNodeInfo) +
           tree_.prim_index.capacity() * sizeof(uint32_t);
  }

  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  const BspTreeData& data() const { return tree_; }
  bool mailboxes() const { return use_mailboxes_; }

 private:
  bool use_mailboxes_;
  BspTreeData tree_;
  Mailboxes mailboxes_;
};

// Where the ray o + t dir meets a node's plane, as the traversal needs it.
struct BspCrossing {
  enum Kind : uint8_t {
    crosses,  // dir leaves the plane at a proven angle: t* lies in [t_lo, t_hi]; below first iff below_first
    stays,    // (nearly) parallel, and the whole interval [t_min, t_max] proven on one side: below iff
              // below_first
    undecided,  // (nearly) parallel and within rounding of the plane somewhere: both children, whole interval
  } kind;
  bool below_first;
  float t_lo, t_hi;
};

// n.o, n.dir and d in double: each product of floats is exact, the sums err by at most gamma(3) of the
// magnitudes summed (bounded here by 2^-50 of them). t* = (d - n.o) / (n.dir) is then known to within
// (e_num + |t*| e_den) / (|den| - e_den), plus its own rounding; the interval is rounded outward to floats.
// t_extent: max(|t_min|, |t_max|) of the node's interval, for the parallel case.
inline BspCrossing bsp_crossing(const BspPlane& plane, const glm::vec3& o, const glm::vec3& dir,
                                float t_extent) {
  constexpr double k2m50 = 0x1p-50;  // the bound's factor (a multiplication, not a call to ldexp)
  const double nx = plane.normal.x, ny = plane.normal.y, nz = plane.normal.z;
  const double ox = nx * o.x, oy = ny * o.y, oz = nz * o.z;
  const double dx = nx * dir.x, dy = ny * dir.y, dz = nz * dir.z;
  const double num = double(plane.offset) - ((ox + oy) + oz);
  const double den = (dx + dy) + dz;
  const double e_num =
      (std::fabs(ox) + std::fabs(oy) + std::fabs(oz) + std::fabs(double(plane.offset))) * k2m50;
  const double e_den = (std::fabs(dx) + std::fabs(dy) + std::fabs(dz)) * k2m50;
  BspCrossing c;
  if (std::fabs(den) > 2.0 * e_den) {
    const double t = num / den;
    // The error of t*, its own rounding, and the rounding to float of t* -+ err: 2^-22 |t| is two float ulps
    // of t (more than half an ulp of t -+ err), 1e-37 an ulp near zero; so the float ends still bound t*.
    const double err =
        (e_num + std::fabs(t) * e_den) / (std::fabs(den) - e_den) + std::fabs(t) * 0x1p-22 + 1e-37;
    c.kind = BspCrossing::crosses;
    // Before t* the ray is on the side it moves away from: below when it moves up the normal.
    c.below_first = den > 0.0;
    c.t_lo = float(t - err);
    c.t_hi = float(t + err);
    return c;
  }
  // Parallel within rounding: n.p(t) - d = -num + t den stays on the origin's side over the interval when
  // |num| beats everything the rounding and t den can add.
  const double reach = double(t_extent) * (std::fabs(den) + e_den) + e_num;
  c.kind = std::fabs(num) > reach ? BspCrossing::stays : BspCrossing::undecided;
  c.below_first = num > 0.0;  // the origin below the plane: n.o < d
  c.t_lo = -kInfinity;
  c.t_hi = kInfinity;
  return c;
}

template <class Recorder>
bool BspTree::traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  *hit = Hit{};
  rec.ray_begin(ray);
  SlabRay slab(ray);
  float t_min, t_max;
  if (tree_.nodes.empty() || !intersect_slabs(tree_.bounds, slab, &t_min, &t_max)) {
    rec.ray_end(*hit);
    return false;
  }
  // As in the kd-tree: a node is skipped, or a hit accepted before a node, only beyond a margin of 2^-12 of
  // the largest t in the root's box, which covers the rounding of the hits' t values.
  const float margin = std::max(std::fabs(t_min), std::fabs(t_max)) * (1.f / 4096.f);

  struct Entry {
    uint32_t node;
    int32_t depth;
    float t_min, t_max;
  };
  Entry stack[kBspMaxDepth + 1];
  int stack_size = 0;

  MailboxStamp mailbox = use_mailboxes_ ? mailboxes_.begin_ray() : MailboxStamp(0, nullptr);
  MailboxStamp* const seen = use_mailboxes_ ? &mailbox : nullptr;
  WatertightRay wray(ray);
  NearestHit nearest(ray.tmax);
  uint32_t node_id = 0;
  int32_t depth = 0;
  const BspNode* nodes = tree_.nodes.data();
  const uint32_t* prim_ids = tree_.prim_index.data();
  for (;;) {
    const BspNode& node = nodes[node_id];
    rec.node(TreeStep{int32_t(node_id), depth, t_min, t_max});

    if (!node.is_leaf()) {
      const BspCrossing c =
          bsp_crossing(node.plane, ray.origin, ray.direction, std::max(std::fabs(t_min), std::fabs(t_max)));
      const uint32_t below = node_id + 1, above = node.above_child();
      const uint32_t near_child = c.below_first ? below : above, far_child = c.below_first ? above : below;
      if (c.kind == BspCrossing::stays || c.t_lo > t_max + margin) {
        node_id = near_child;  // parallel on one side, or the ray leaves the node before it reaches the plane
      } else if (c.kind == BspCrossing::crosses && c.t_hi < t_min - margin) {
        node_id = far_child;  // the ray crossed the plane before it entered the node
      } else if (c.kind == BspCrossing::undecided) {
        // Lying in the plane, or too nearly parallel to tell: both children over the whole interval.
        rec.push(TreeStep{int32_t(far_child), depth + 1, t_min, t_max});
        stack[stack_size++] = Entry{far_child, depth + 1, t_min, t_max};
        node_id = near_child;
      } else {
        // Both: Intersect(near, t_min, t*) now, push (far, t*, t_max); t* as its interval's ends.
        const float far_min = std::min(std::max(c.t_lo, t_min), t_max);
        const float near_max = std::max(std::min(c.t_hi, t_max), t_min);
        rec.push(TreeStep{int32_t(far_child), depth + 1, far_min, t_max});
        stack[stack_size++] = Entry{far_child, depth + 1, far_min, t_max};
        node_id = near_child;
        t_max = near_max;
      }
      ++depth;
      continue;
    }

    rec.leaf(TreeStep{int32_t(node_id), depth, t_min, t_max});
    const uint32_t* prims = prim_ids + node.first_prim();
    const uint32_t n = node.prim_count();
    for (uint32_t i = 0; i < n; ++i) geometry_->prefetch(prims[i]);
    for (uint32_t i = 0; i < n; ++i)
      if (nearest.test(*geometry_, prims[i], ray, wray, seen, rec) && any_hit) break;
    if (any_hit && nearest.found()) {
      rec.hit_accepted(uint32_t(nearest.hit.prim), nearest.t, AcceptReason::any_hit);
      break;
    }

    // Pop the next far child. The entries' t_min are not ordered (t* is an interval, and a parallel ray's
    // entries span the whole interval), so an entry is skipped on its own merit and the rest still looked at:
    // a hit is accepted only once no entry left can hold a nearer one.
    bool more = false;
    AcceptReason reason = AcceptReason::structure_done;
    while (stack_size > 0) {
      const Entry& e = stack[--stack_size];
      rec.pop(TreeStep{int32_t(e.node), e.depth, e.t_min, e.t_max});
      if (nearest.found() && nearest.t < e.t_min - margin) {
        reason = AcceptReason::next_node_beyond;
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
      if (nearest.found()) rec.hit_accepted(uint32_t(nearest.hit.prim), nearest.t, reason);
      break;
    }
  }
  *hit = nearest.hit;
  rec.ray_end(*hit);
  return hit->found();
}

}  // namespace raystep
