// The plain SAH kd-tree builder, the reference that the Wald-Havran sweep (kdtree_build_sah.cpp) is tested
// against: the same decisions, computed without events. For each node and axis, every distinct position of a
// clipped bound strictly inside the node is a candidate, and N_below, N_above, N_planar are counted by a loop
// over all the node's primitives: O(N^2) per node. For tests, and for reading beside the lecture.
#include <algorithm>
#include <vector>

#include "kdtree_build_common.h"

namespace raystep::kd {
namespace {

template <class Recorder>
class ReferenceBuilder : public PrimRefBuilder<ReferenceBuilder<Recorder>, Recorder> {
  using Base = PrimRefBuilder<ReferenceBuilder<Recorder>, Recorder>;
  friend Base;
  using Base::geometry_;
  using Base::make_leaf;
  using Base::out_;
  using Base::rec_;

 public:
  using Base::Base;

 private:
  void build_node(const Bounds3& box, int32_t parent, int32_t depth, size_t budget,
                  std::vector<PrimRef> prims) {
    const uint32_t node = out_.add_node(box, parent, depth);
    const SahModel& model = out_.model();
    const uint32_t n = uint32_t(prims.size());
    const float leaf_cost = model.leaf_cost(n);

    // 1. Leaves made without a search.
    if (n <= uint32_t(out_.options().leaf_size))
      return make_leaf(node, prims, leaf_cost, LeafReason::few_primitives);
    if (depth >= out_.max_depth()) return make_leaf(node, prims, leaf_cost, LeafReason::max_depth);

    // 2. Every candidate plane: the distinct clipped bounds strictly inside the node, in the order axis x, y,
    // z
    //    and increasing position; each one counted against every primitive.
    bool record = false;
    if constexpr (Recorder::enabled) record = rec_.wants_candidates(node);
    const float area_node = out_.space().measure(box);
    SahCandidate best;
    bool found = false;
    for (int axis = 0; axis < out_.space().axes && area_node > 0.f; ++axis) {
      const SplitMeasure areas(box, axis, out_.space());
      std::vector<float> positions;
      for (const PrimRef& r : prims)
        for (float x : {r.bounds.lo[axis], r.bounds.hi[axis]})
          if (box.lo[axis] < x && x < box.hi[axis]) positions.push_back(x);
      std::sort(positions.begin(), positions.end());
      positions.erase(std::unique(positions.begin(), positions.end()), positions.end());

      for (float x : positions) {
        uint32_t n_left = 0, n_right = 0, n_planar = 0;
        for (const PrimRef& r : prims) {
          float lo = r.bounds.lo[axis], hi = r.bounds.hi[axis];
          if (lo == x && hi == x) ++n_planar;
          if (lo < x) ++n_left;
          if (hi > x) ++n_right;
        }
        SahCandidate c = model.candidate(areas, x, n_left, n_right, n_planar);
        if constexpr (Recorder::enabled)
          if (record) rec_.sah_candidate(node, c);
        if (!found || cheaper(c, best)) {
          best = c;
          found = true;
        }
      }
    }

    // 3. Leaves decided by the search.
    if (!found) return make_leaf(node, prims, leaf_cost, LeafReason::no_candidate);
    if (!(best.cost < leaf_cost)) return make_leaf(node, prims, leaf_cost, LeafReason::no_cheaper_split);
    if (!budget_allows(budget, best.n_below, best.n_above))
      return make_leaf(node, prims, leaf_cost, LeafReason::budget);

    // 4. Split: classify into the children, then build below, then above (depth-first preorder).
    out_.set_split_cost(node, best.cost);
    rec_.split(node, out_.info(node), n, best.axis, best.position, best.cost, leaf_cost);
    Bounds3 below_box = box, above_box = box;
    below_box.hi[best.axis] = best.position;
    above_box.lo[best.axis] = best.position;
    std::vector<PrimRef> below, above;
    classify_prim_refs(geometry_, prims, best.axis, best.position, best.planar_below, below_box, above_box,
                       &below, &above);
    std::vector<PrimRef>().swap(prims);
    uint32_t above_child = build_children(
        out_, budget, best.n_below, best.n_above,
        [&](size_t b) { build_node(below_box, int32_t(node), depth + 1, b, std::move(below)); },
        [&](size_t b) { build_node(above_box, int32_t(node), depth + 1, b, std::move(above)); });
    out_.set_inner(node, best.axis, best.position, above_child);
  }
};

}  // namespace

template <class Recorder>
KdTreeData build_sah_reference(const Geometry& geometry, const KdOptions& options, Recorder& rec) {
  return ReferenceBuilder<Recorder>(geometry, options, rec).build();
}

template KdTreeData build_sah_reference(const Geometry&, const KdOptions&, NullBuildRecorder&);
template KdTreeData build_sah_reference(const Geometry&, const KdOptions&, BuildListenerRecorder&);

}  // namespace raystep::kd
