// The octree accelerator (lecture: "oct-tree"), walked front to back by the parametric algorithm of Revelles,
// Urena and Lastra ("An efficient parametric algorithm for octree traversal", 2000): a node is the ray's
// entry and exit parameters on its three pairs of planes; its children's parameters are those and the centre
// planes' t; the first child follows from the entry plane, the next from the exit plane (a table), so the
// children are met in the order the ray crosses them. A negative direction is reflected (the paper's trick),
// here on the child indices, so that no coordinate is rounded. An explicit stack of nodes, mailboxes as in
// the grid, and "traverse until tmin(cell) > tmax(ray)". In the plane of a 2D scene the same walk is the
// quadtree's: cells cut on x and y only, four children each (OctreeData::axes), the kernel instantiated for
// two axes once per ray.
#pragma once

#include <algorithm>
#include <cmath>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/mailbox.h"
#include "raystep/accel/nearest_hit.h"
#include "raystep/accel/octree_build.h"
#include "raystep/accel/recorded_walk.h"
#include "raystep/record/recorder.h"

namespace raystep {

class Octree final : public RecordedWalk<Octree, OctreeOptions> {
 public:
  explicit Octree(OctreeOptions options = {}) : RecordedWalk(options) {}
  std::string name() const override { return "octree"; }
  void build(const Geometry& geometry) override;
  size_t memory_bytes() const override {
    return tree_.nodes.capacity() * sizeof(OctreeNode) + tree_.info.capacity() * sizeof(OctreeNodeInfo) +
           tree_.prim_index.capacity() * sizeof(uint32_t);
  }

  // The traversal kernel, instrumented through the recorder (see record/recorder.h).
  template <class Recorder>
  bool traverse(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
    return tree_.axes == 2 ? walk<2>(ray, hit, any_hit, rec) : walk<3>(ray, hit, any_hit, rec);
  }

  const OctreeData& data() const { return tree_; }
  const OctreeStats& stats() const { return stats_; }  // counted once, at the build (a trace names them)

  // The paper's exit table: from child c (reflected indices, bit a = upper half on axis a) leaving by the
  // plane normal to axis a, the next child is c with bit a set; 8 when that bit is set already: the ray
  // leaves the parent.
  static constexpr uint8_t kNextChild[8][3] = {{1, 2, 4}, {8, 3, 5}, {3, 8, 6}, {8, 8, 7},
                                               {5, 6, 8}, {8, 7, 8}, {7, 8, 8}, {8, 8, 8}};
  // The paper's first child: entering by the plane normal to axis `entry` at t_in, the child is upper on each
  // other axis (of the kAxes cut) whose centre plane the ray crossed before t_in.
  template <int kAxes = 3>
  static int first_child(const float mid_t[3], float t_in, int entry) {
    int c = 0;
    for (int b = 0; b < kAxes; ++b)
      if (b != entry && mid_t[b] < t_in) c |= 1 << b;
    return c;
  }

 private:
  // The walk of a tree whose cells are cut on the first kAxes axes (3: the octree; 2: the quadtree of a 2D
  // scene, whose cells keep the root's z extent: no centre plane on z, so its exit is the cell's own).
  template <int kAxes, class Recorder>
  bool walk(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const;

  OctreeData tree_;
  OctreeStats stats_;
  Mailboxes mailboxes_;
};

template <int kAxes, class Recorder>
bool Octree::walk(const Ray& ray, Hit* hit, bool any_hit, Recorder& rec) const {
  constexpr int kChildren = 1 << kAxes;
  *hit = Hit{};
  rec.ray_begin(ray);
  SlabRay slab(ray);
  float t_enter, t_exit;
  if (tree_.nodes.empty() || !intersect_slabs(tree_.bounds, slab, &t_enter, &t_exit)) {
    rec.ray_end(*hit);
    return false;
  }
  // Computed t values stray a few ulps from the exact plane distances: a child whose computed interval is
  // empty by less than select_margin is still walked (the ray may graze it), and a hit is accepted, or a
  // child skipped, only beyond hit_margin (primitive t values stray further: slivers ~1e-5), as in kdtree.h.
  const float scale = std::max(std::fabs(t_enter), std::fabs(t_exit));
  const float select_margin = scale * (1.f / 65536.f), hit_margin = scale * (1.f / 4096.f);

  // The reflection: bit a of `mask` is set for a negative direction (also -0) on axis a; reflected child c is
  // real child c ^ mask, and t0, t1 below are the entry and exit parameters in the reflected frame. An axis
  // the ray does not move along (0, or so small that 1/d overflows) has t0 = -inf, t1 = +inf and its centre
  // plane's t is -inf or +inf by the origin's side: never 0 * inf.
  int mask = 0;
  bool moving[3];
  for (int a = 0; a < 3; ++a) {
    if (a < kAxes) mask |= int(std::signbit(ray.direction[a])) << a;
    moving[a] = std::isfinite(slab.inv_dir[a]);
  }
  auto plane_t = [&](float x, int a) { return (x - ray.origin[a]) * slab.inv_dir[a]; };

  struct Frame {  // an inner node whose children are being walked
    uint32_t node;
    int32_t depth;
    Bounds3 box;
    float mid[3];  // the centre planes' coordinates
    float t0[3], t1[3], mid_t[3];
    uint8_t order[8];  // reflected child indices in visit order
    uint8_t count, next;
  };
  Frame stack[kOctreeMaxDepth + 1];
  int stack_size = 0;

  // The node about to be visited.
  uint32_t node_id = 0;
  int32_t depth = 0;
  const Frame* parent = nullptr;  // the node's parent frame (none for the root), and which child it is
  int real_child = 0;
  float t0[3], t1[3];
  for (int a = 0; a < 3; ++a) {
    bool neg = std::signbit(ray.direction[a]);
    t0[a] = moving[a] ? plane_t(neg ? tree_.bounds.hi[a] : tree_.bounds.lo[a], a) : -kInfinity;
    t1[a] = moving[a] ? plane_t(neg ? tree_.bounds.lo[a] : tree_.bounds.hi[a], a) : kInfinity;
  }

  MailboxStamp mailbox = mailboxes_.begin_ray();
  WatertightRay wray(ray);
  NearestHit nearest(ray.tmax);
  AcceptReason reason = AcceptReason::structure_done;
  const OctreeNode* nodes = tree_.nodes.data();
  const uint32_t* prim_ids = tree_.prim_index.data();
  for (;;) {
    const OctreeNode& node = nodes[node_id];
    const float t_in = std::max({t0[0], t0[1], t0[2]}), t_out = std::min({t1[0], t1[1], t1[2]});
    // The part of the ray's interval inside the cell (a grazed cell's may be empty: shown as a point).
    const float t_min = std::max(t_in, t_enter), t_max = std::max(t_min, std::min(t_out, t_exit));
    rec.node(TreeStep{int32_t(node_id), depth, t_min, t_max});

    if (!node.is_leaf()) {
      // The children are one block (eight: 64 bytes): start loading it now, while their order is worked out.
      __builtin_prefetch(&nodes[node.first]);
      Frame& f = stack[stack_size++];
      f.node = node_id;
      f.depth = depth;
      // The cell, worked out only for an inner node: the octant of its parent's cell its bits name.
      for (int a = 0; a < 3; ++a) {
        bool up = (real_child >> a) & 1;
        f.box.lo[a] = !parent ? tree_.bounds.lo[a] : up ? parent->mid[a] : parent->box.lo[a];
        f.box.hi[a] = !parent ? tree_.bounds.hi[a] : up ? parent->box.hi[a] : parent->mid[a];
      }
      for (int a = 0; a < 3; ++a) {
        f.t0[a] = t0[a];
        f.t1[a] = t1[a];
        if (a >= kAxes) {  // not cut: every child spans the cell, and leaves it by the cell's own face
          f.mid[a] = f.box.hi[a];
          f.mid_t[a] = t1[a];
          continue;
        }
        float mid = f.mid[a] = 0.5f * (f.box.lo[a] + f.box.hi[a]);  // the build's centre (octree_build.cpp)
        bool upper_side = ray.origin[a] >= mid;  // a ray in the centre plane goes to the upper half
        f.mid_t[a] =
            moving[a] ? plane_t(mid, a) : (upper_side != bool((mask >> a) & 1) ? -kInfinity : kInfinity);
      }
      // The children in the order the ray crosses them: the first by the entry plane, each next by the plane
      // it leaves by (ties to the lowest axis).
      int entry = t0[0] >= t0[1] && t0[0] >= t0[2] ? 0 : (t0[1] >= t0[2] ? 1 : 2);
      float c_in[kChildren];
      bool on_path[kChildren] = {};
      // A near tie (a centre plane crossed within select_margin of the entry, or two exit planes within it of
      // each other: the ray passes close to an edge or corner of the children) may hide a grazed child.
      bool tie = false;
      for (int b = 0; b < kAxes; ++b) tie |= b != entry && !(std::fabs(f.mid_t[b] - t_in) > select_margin);
      f.count = 0;
      for (int c = first_child<kAxes>(f.mid_t, t_in, entry); c < kChildren;) {
        float ct1[3];
        for (int a = 0; a < 3; ++a) ct1[a] = (c >> a) & 1 ? f.t1[a] : f.mid_t[a];
        int exit = ct1[0] <= ct1[1] && ct1[0] <= ct1[2] ? 0 : (ct1[1] <= ct1[2] ? 1 : 2);
        for (int a = 0; a < 3; ++a) tie |= a != exit && !(ct1[a] - ct1[exit] > select_margin);
        on_path[c] = true;
        f.order[f.count++] = uint8_t(c);
        c = exit < kAxes ? kNextChild[c][exit] : kChildren;  // an uncut axis's face is the parent's
      }
      // Then a child off the path whose interval is empty only by a rounding margin is grazed: walk it too,
      // in entry order (a rounded t must never skip a cell the exact ray passes through).
      for (int i = 0; tie && i < f.count; ++i) {
        int c = f.order[i];
        c_in[i] = std::max(
            {(c & 1) ? f.mid_t[0] : f.t0[0], (c & 2) ? f.mid_t[1] : f.t0[1], (c & 4) ? f.mid_t[2] : f.t0[2]});
      }
      for (int c = 0; tie && c < kChildren; ++c) {
        if (on_path[c]) continue;
        float ct0[3], ct1[3];
        for (int a = 0; a < 3; ++a) {
          bool up = (c >> a) & 1;
          ct0[a] = up ? f.mid_t[a] : f.t0[a];
          ct1[a] = up ? f.t1[a] : f.mid_t[a];
        }
        float c_t_in = std::max({ct0[0], ct0[1], ct0[2]}), c_t_out = std::min({ct1[0], ct1[1], ct1[2]});
        if (!(c_t_in <= c_t_out + select_margin)) continue;
        int i = f.count++;
        for (; i > 0 && c_in[i - 1] > c_t_in; --i) {
          f.order[i] = f.order[i - 1];
          c_in[i] = c_in[i - 1];
        }
        f.order[i] = uint8_t(c);
        c_in[i] = c_t_in;
      }
      f.next = 0;
      rec.push(TreeStep{int32_t(node_id), depth, t_min, t_max});
    } else {
      // Leaf: test its primitives, skipping those already tested for this ray (mailbox).
      rec.leaf(TreeStep{int32_t(node_id), depth, t_min, t_max});
      const uint32_t* prims = prim_ids + node.first;
      const uint32_t n = node.prim_count();
      for (uint32_t i = 0; i < n; ++i) {
        uint32_t prim = prims[i];
        if (!nearest.test(*geometry_, prim, ray, wray, &mailbox, rec)) continue;
        if (any_hit) {
          rec.hit_accepted(prim, nearest.t, AcceptReason::any_hit);
          *hit = nearest.hit;
          rec.ray_end(*hit);
          return true;
        }
        // A hit beyond this cell's exit may yet be beaten by a primitive of a later cell: keep it, go on.
        if (nearest.t + hit_margin >= t_max) rec.hit_deferred(prim, nearest.t, t_max);
      }
      // Traverse until tmin(next cell) > tmax(ray): every later cell starts at this one's exit.
      if (nearest.found() && nearest.t + hit_margin < t_max) {
        rec.hit_accepted(uint32_t(nearest.hit.prim), nearest.t, AcceptReason::inside_cell);
        break;
      }
    }

    // The next child: of the deepest node with children left. Each node's children are in entry order, so one
    // that starts beyond the ray's end or the nearest hit ends its node's walk.
    bool more = false;
    while (stack_size > 0) {
      Frame& f = stack[stack_size - 1];
      if (f.next == f.count) {
        --stack_size;
        if constexpr (Recorder::enabled) {
          float f_in = std::max({f.t0[0], f.t0[1], f.t0[2]}), f_out = std::min({f.t1[0], f.t1[1], f.t1[2]});
          float f_min = std::max(f_in, t_enter);
          rec.pop(TreeStep{int32_t(f.node), f.depth, f_min, std::max(f_min, std::min(f_out, t_exit))});
        } else {
          rec.pop(TreeStep{});
        }
        continue;
      }
      const int c = f.order[f.next++];
      for (int a = 0; a < 3; ++a) {
        bool up = (c >> a) & 1;
        t0[a] = up ? f.mid_t[a] : f.t0[a];
        t1[a] = up ? f.t1[a] : f.mid_t[a];
      }
      const float c_in = std::max({t0[0], t0[1], t0[2]}), c_out = std::min({t1[0], t1[1], t1[2]});
      if (c_out < t_enter - select_margin) continue;  // behind the ray's start (a ray starting inside)
      if (c_in > t_exit + select_margin) {            // beyond the ray's end, and so are the rest
        f.next = f.count;
        continue;
      }
      if (nearest.found() && nearest.t + hit_margin < c_in) {  // tmin(cell) > tmax(ray), and the rest too
        reason = AcceptReason::next_node_beyond;
        f.next = f.count;
        continue;
      }
      real_child = c ^ mask;
      parent = &f;
      node_id = nodes[f.node].child(real_child);
      depth = f.depth + 1;
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
