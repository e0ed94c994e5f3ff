// What the three kd-tree builders share (kdtree_build_sah.cpp, kdtree_build_reference.cpp,
// kdtree_build_median.cpp): a primitive's bounds clipped to a node ("perfect splits"), the SAH cost of one
// candidate plane with the planar primitives on the cheaper side (Wald and Havran 2006, section 4.2), and the
// tree being written with its depth limit and reference budget. Internal to raystep_core.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/kdtree_build.h"
#include "raystep/geometry/bounds.h"
#include "raystep/scene/geometry.h"

namespace raystep::kd {

// The bounds of primitive `prim` inside `box`: a triangle clipped to the box (Sutherland-Hodgman, rounded
// outward), a sphere's bounding box intersected with the box. -0 becomes +0, so that equal positions have
// equal bits in every builder.
Bounds3 clipped_bounds(const Geometry& geometry, uint32_t prim, const Bounds3& box);

// A straddling primitive's bounds in one child. When in doubt, both: should clipping leave nothing (the
// primitive reaches the child only within rounding), it keeps its own bounds intersected with the child.
Bounds3 straddler_bounds(const Geometry& geometry, uint32_t prim, const Bounds3& child);
// The same for both children of `box` cut at `position` on `axis`, at once (the sweep's split step): bit for
// bit straddler_bounds(.., below child) and straddler_bounds(.., above child), by clip_triangle_bounds_split.
void straddler_bounds_split(const Geometry& geometry, uint32_t prim, const Bounds3& box, int axis,
                            float position, Bounds3* below, Bounds3* above);

// The SAH cost model: C = t_t + t_i (p_b N_b + p_a N_a), p = S_child / S_node; with an empty child and
// empty_bonus > 0, C = t_t + (1 - bonus) t_i (p_b N_b + p_a N_a) (pbrt's form). A leaf costs N t_i.
struct SahModel {
  float t_t, t_i, empty_bonus;

  float leaf_cost(uint32_t n) const { return t_i * float(n); }

  // Written in the order of the inspector's CSV contract: t_t + t_i * (S_b/S * N_b + S_a/S * N_a).
  float cost(float area_below, float area_above, float area_node, uint32_t n_below, uint32_t n_above) const {
    float weighted = area_below / area_node * float(n_below) + area_above / area_node * float(n_above);
    float bonus = (n_below == 0 || n_above == 0) ? empty_bonus : 0.f;
    return t_t + (1.f - bonus) * t_i * weighted;
  }

  // The candidate at `position` on `axis`: n_left primitives reach below the plane, n_right above, n_planar
  // lie in it. The planar ones are tried on both sides and put on the cheaper one; below on a tie.
  SahCandidate candidate(const SplitMeasure& areas, float position, uint32_t n_left, uint32_t n_right,
                         uint32_t n_planar) const {
    SahCandidate c;
    c.axis = areas.axis;
    c.position = position;
    c.n_planar = n_planar;
    c.area_below = areas.below(position);
    c.area_above = areas.above(position);
    c.area_node = areas.node;
    c.n_below = n_left + n_planar;
    c.n_above = n_right;
    c.cost = cost(c.area_below, c.area_above, c.area_node, c.n_below, c.n_above);
    c.planar_below = true;
    if (n_planar > 0) {
      float cost_above = cost(c.area_below, c.area_above, c.area_node, n_left, n_right + n_planar);
      if (cost_above < c.cost) {
        c.n_below = n_left;
        c.n_above = n_right + n_planar;
        c.cost = cost_above;
        c.planar_below = false;
      }
    }
    return c;
  }
};

// The tie rule, given candidates offered in the order axis x, y, z and increasing position: a later
// candidate replaces the best only when strictly cheaper.
inline bool cheaper(const SahCandidate& c, const SahCandidate& best) {
  return c.cost < best.cost;
}

// The reference budget, shared out down the tree: the root has kd_reference_budget(N); a node may split only
// if its children's primitives fit, n_below + n_above <= its budget. The below child (built first) gets a
// share in proportion to n_below, at least its own count; the above child gets the rest of the node's budget,
// including whatever the below subtree left unused. So the leaves' references never exceed the root's budget,
// the above side is never starved by the below side, and the budget binds only where the duplication really
// piles up (on the bunny, nowhere; on 100,000 identical triangles, at once).
inline bool budget_allows(size_t budget, uint32_t n_below, uint32_t n_above) {
  return size_t(n_below) + n_above <= budget;
}

// The tree as it is written, node by node in depth-first preorder, with the build's limits.
class TreeWriter {
 public:
  TreeWriter(const Geometry& geometry, const KdOptions& options);

  const KdOptions& options() const { return options_; }
  const SahModel& model() const { return model_; }
  SplitSpace space() const { return tree_.space; }
  int max_depth() const { return max_depth_; }

  // A new node (its kind is set later); throws InputError when the node array is full.
  uint32_t add_node(const Bounds3& box, int32_t parent, int32_t depth);
  const KdNodeInfo& info(uint32_t node) const { return tree_.info[node]; }
  // prims: the leaf's primitive ids in increasing order.
  void set_leaf(uint32_t node, const uint32_t* prims, uint32_t count, float cost);
  // The split's cost is set when it is chosen (so that the recorder sees it), the above child once it exists.
  void set_split_cost(uint32_t node, float cost) { tree_.info[node].cost = cost; }
  void set_inner(uint32_t node, int axis, float split, uint32_t above_child);
  uint32_t node_count() const { return uint32_t(tree_.nodes.size()); }
  // The primitive references the leaves written so far hold.
  size_t reference_count() const { return tree_.prim_index.size(); }

  // The root's reference budget.
  size_t root_budget() const { return budget_; }

  // The arrays were reserved for the largest tree; give back what the built one does not use (a median tree
  // of the bunny holds a third of the reservation), so that its memory is what it needs.
  KdTreeData finish() {
    tree_.nodes.shrink_to_fit();
    tree_.info.shrink_to_fit();
    tree_.prim_index.shrink_to_fit();
    return std::move(tree_);
  }

 private:
  KdOptions options_;
  SahModel model_;
  int max_depth_;
  size_t budget_;
  KdTreeData tree_;
};

// A split node's children, built depth first with the budget shared out as described above:
// build_below(budget) then build_above(budget), each building its whole subtree. Returns the above child's
// id.
template <class BuildBelow, class BuildAbove>
uint32_t build_children(TreeWriter& out, size_t budget, uint32_t n_below, uint32_t n_above,
                        BuildBelow build_below, BuildAbove build_above) {
  const size_t refs_before = out.reference_count();
  build_below(size_t(uint64_t(budget) * n_below / (uint64_t(n_below) + n_above)));
  const size_t used_below = out.reference_count() - refs_before;
  const uint32_t above_child = out.node_count();
  build_above(budget - used_below);
  return above_child;
}

// The list-based builders (reference and median) carry each primitive with its bounds clipped to the node.
struct PrimRef {
  uint32_t prim;
  Bounds3 bounds;
};

// Every primitive of the scene with its bounds in the root box, in id order.
std::vector<PrimRef> root_prim_refs(const Geometry& geometry);

// Classification into the children of the plane (axis, position): below if the clipped bounds reach below the
// plane, above if they reach above, both (re-clipped to each child) if they straddle it; planar primitives
// (lo = hi = position) to the side planar_below says. The id order is kept.
void classify_prim_refs(const Geometry& geometry, const std::vector<PrimRef>& prims, int axis, float position,
                        bool planar_below, const Bounds3& below_box, const Bounds3& above_box,
                        std::vector<PrimRef>* below, std::vector<PrimRef>* above);

// What the list-based builders share: the tree being written, the recorder, the root's call, and a leaf made
// of a PrimRef list. Derived provides build_node(box, parent, depth, budget, prims) (CRTP: no virtual call).
template <class Derived, class Recorder>
class PrimRefBuilder {
 public:
  PrimRefBuilder(const Geometry& geometry, const KdOptions& options, Recorder& rec)
      : geometry_(geometry), out_(geometry, options), rec_(rec) {}

  KdTreeData build() {
    static_cast<Derived*>(this)->build_node(geometry_.bounds(), -1, 0, out_.root_budget(),
                                            root_prim_refs(geometry_));
    return out_.finish();
  }

 protected:
  void make_leaf(uint32_t node, const std::vector<PrimRef>& prims, float leaf_cost, LeafReason reason) {
    std::vector<uint32_t> ids;
    ids.reserve(prims.size());
    for (const PrimRef& r : prims) ids.push_back(r.prim);  // already in increasing id order
    out_.set_leaf(node, ids.data(), uint32_t(ids.size()), leaf_cost);
    rec_.leaf_made(node, out_.info(node), uint32_t(prims.size()), leaf_cost, reason);
  }

  const Geometry& geometry_;
  TreeWriter out_;
  Recorder& rec_;
};

// The builder kernels, explicitly instantiated for NullBuildRecorder and BuildListenerRecorder.
template <class Recorder>
KdTreeData build_sah(const Geometry& geometry, const KdOptions& options, Recorder& rec);
template <class Recorder>
KdTreeData build_sah_reference(const Geometry& geometry, const KdOptions& options, Recorder& rec);
template <class Recorder>
KdTreeData build_median(const Geometry& geometry, const KdOptions& options, Recorder& rec);

}  // namespace raystep::kd
