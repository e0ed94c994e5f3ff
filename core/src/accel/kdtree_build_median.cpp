// The spatial-median kd-tree builder of the lesson "why SAH wins": every node is cut across its longest axis
// at the middle, whatever the primitives do there (the lecture's first kd-tree, before the SAH). The
// primitives are classified by their clipped bounds like the SAH builders do. The median plane's SAH cost is
// recorded all the same (node info, the recorder's one candidate), so the two trees can be compared.
// Leaves: N <= leaf_size, the depth limit, a plane that would separate nothing (every primitive straddles it:
// no_candidate), and the reference budget, which without a cost to stop it is what bounds a median tree.
#include <vector>

#include "kdtree_build_common.h"

namespace raystep::kd {
namespace {

template <class Recorder>
class MedianBuilder : public PrimRefBuilder<MedianBuilder<Recorder>, Recorder> {
  using Base = PrimRefBuilder<MedianBuilder<Recorder>, Recorder>;
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
    const uint32_t n = uint32_t(prims.size());
    const float leaf_cost = out_.model().leaf_cost(n);
    if (n <= uint32_t(out_.options().leaf_size))
      return make_leaf(node, prims, leaf_cost, LeafReason::few_primitives);
    if (depth >= out_.max_depth()) return make_leaf(node, prims, leaf_cost, LeafReason::max_depth);

    // The plane: the middle of the node's longest axis.
    const int axis = out_.space().longest_axis(box);
    const float position = box.center()[axis];
    const float area_node = out_.space().measure(box);
    if (!(box.lo[axis] < position && position < box.hi[axis]) || !(area_node > 0.f))
      return make_leaf(node, prims, leaf_cost, LeafReason::no_candidate);

    // Its counts and SAH cost (planar primitives on the cheaper side), for the record.
    uint32_t n_left = 0, n_right = 0, n_planar = 0;
    for (const PrimRef& r : prims) {
      float lo = r.bounds.lo[axis], hi = r.bounds.hi[axis];
      if (lo == position && hi == position) ++n_planar;
      if (lo < position) ++n_left;
      if (hi > position) ++n_right;
    }
    SahCandidate c =
        out_.model().candidate(SplitMeasure(box, axis, out_.space()), position, n_left, n_right, n_planar);
    if constexpr (Recorder::enabled)
      if (rec_.wants_candidates(node)) rec_.sah_candidate(node, c);
    if (c.n_below == n && c.n_above == n) return make_leaf(node, prims, leaf_cost, LeafReason::no_candidate);
    if (!budget_allows(budget, c.n_below, c.n_above))
      return make_leaf(node, prims, leaf_cost, LeafReason::budget);

    // Split, then build below, then above.
    out_.set_split_cost(node, c.cost);
    rec_.split(node, out_.info(node), n, axis, position, c.cost, leaf_cost);
    Bounds3 below_box = box, above_box = box;
    below_box.hi[axis] = position;
    above_box.lo[axis] = position;
    std::vector<PrimRef> below, above;
    classify_prim_refs(geometry_, prims, axis, position, c.planar_below, below_box, above_box, &below,
                       &above);
    std::vector<PrimRef>().swap(prims);
    uint32_t above_child = build_children(
        out_, budget, c.n_below, c.n_above,
        [&](size_t b) { build_node(below_box, int32_t(node), depth + 1, b, std::move(below)); },
        [&](size_t b) { build_node(above_box, int32_t(node), depth + 1, b, std::move(above)); });
    out_.set_inner(node, axis, position, above_child);
  }
};

}  // namespace

template <class Recorder>
KdTreeData build_median(const Geometry& geometry, const KdOptions& options, Recorder& rec) {
  return MedianBuilder<Recorder>(geometry, options, rec).build();
}

template KdTreeData build_median(const Geometry&, const KdOptions&, NullBuildRecorder&);
template KdTreeData build_median(const Geometry&, const KdOptions&, BuildListenerRecorder&);

}  // namespace raystep::kd
