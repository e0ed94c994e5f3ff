// kd-tree construction: options, limits, dispatch to the builders, the shared pieces of
// kdtree_build_common.h, and the statistics of a built tree.
#include "raystep/accel/kdtree_build.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "kdtree_build_common.h"
#include "raystep/geometry/triangle_clip.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, "kd-tree: " + what);
}

void validate(const Geometry& geometry, const KdOptions& o) {
  if (o.builder != KdBuilder::sah && o.builder != KdBuilder::sah_reference && o.builder != KdBuilder::median)
    fail("unknown builder");
  if (!std::isfinite(o.t_i) || !(o.t_i > 0.f)) fail("t_i must be a finite number > 0");
  if (!std::isfinite(o.t_t) || !(o.t_t >= 0.f)) fail("t_t must be a finite number >= 0");
  if (!std::isfinite(o.empty_bonus) || !(o.empty_bonus >= 0.f && o.empty_bonus < 1.f))
    fail("empty_bonus must be in [0, 1)");
  if (o.max_depth < 0 || o.max_depth > kKdMaxDepth)
    fail("max_depth must be in 0.." + std::to_string(kKdMaxDepth) + " (0: automatic)");
  if (o.leaf_size < 1) fail("leaf_size must be at least 1");
  if (!std::isfinite(o.reference_budget) || !(o.reference_budget >= 1.f))
    fail("reference_budget must be a finite number >= 1");
  if (geometry.size() > KdNode::kMaxIndex)
    fail("more than " + std::to_string(KdNode::kMaxIndex) + " primitives");
  // Non-finite coordinates would break the sort of the events (and can never be hit).
  for (uint32_t id = 0; id < geometry.size(); ++id) {
    Bounds3 b = geometry.prim_bounds(id);
    if (!is_finite(b.lo) || !is_finite(b.hi)) fail("primitive " + std::to_string(id) + " is not finite");
  }
}

template <class Recorder>
KdTreeData dispatch(const Geometry& geometry, const KdOptions& options, Recorder& rec) {
  validate(geometry, options);
  switch (options.builder) {
    case KdBuilder::sah_reference:
      return kd::build_sah_reference(geometry, options, rec);
    case KdBuilder::median:
      return kd::build_median(geometry, options, rec);
    case KdBuilder::sah:
    default:
      return kd::build_sah(geometry, options, rec);
  }
}

// -0 and +0 compare equal; make them the same bits too.
inline Bounds3 without_negative_zero(Bounds3 b) {
  b.lo += glm::vec3(0.f);
  b.hi += glm::vec3(0.f);
  return b;
}

}  // namespace

int kd_max_depth(const KdOptions& options, size_t prim_count) {
  if (options.max_depth > 0) return std::min(options.max_depth, kKdMaxDepth);
  // With t_i = 80 t_t the SAH keeps cutting slivers of empty space off small nodes until the depth limit
  // stops it; pbrt's 8 + 1.3 log2 N lets it go on far beyond what pays off on real hardware (the bunny: 906k
  // nodes, every leaf at the limit). 1.2 log2 N leaves a few levels for the empty space beyond a balanced
  // tree; measured fastest or level on the bunny, the teapot, the small bunny and the torus knot
  // (bench/README.md). An empty bonus spends a level on every slab of empty space it cuts off, so with one
  // the limit stays pbrt's (at 1.2 log2 N the bunny's leaves would hold up to 780 triangles).
  double n = double(std::max<size_t>(prim_count, 1));
  double depth = options.empty_bonus > 0.f ? 8.0 + 1.3 * std::log2(n) : 1.2 * std::log2(n);
  return std::min(kKdMaxDepth, std::max(8, int(std::lround(depth))));
}

size_t kd_reference_budget(const KdOptions& options, size_t prim_count) {
  double budget = std::ceil(double(options.reference_budget) * double(prim_count));
  budget = std::min(budget, double(KdNode::kMaxIndex));
  return std::max(prim_count, size_t(budget));
}

const char* leaf_reason_name(LeafReason reason) {
  switch (reason) {
    case LeafReason::few_primitives:
      return "few_primitives";
    case LeafReason::max_depth:
      return "max_depth";
    case LeafReason::no_cheaper_split:
      return "no_cheaper_split";
    case LeafReason::no_candidate:
      return "no_candidate";
    case LeafReason::budget:
      return "budget";
  }
  return "unknown";
}

KdTreeData build_kdtree(const Geometry& geometry, const KdOptions& options) {
  NullBuildRecorder rec;
  return dispatch(geometry, options, rec);
}

KdTreeData build_kdtree(const Geometry& geometry, const KdOptions& options, BuildListener& listener) {
  BuildListenerRecorder rec{&listener};
  return dispatch(geometry, options, rec);
}

KdTreeStats kd_tree_stats(const KdTreeData& tree, const KdOptions& options) {
  KdTreeStats s;
  s.nodes = tree.nodes.size();
  s.references = tree.prim_index.size();
  double root_area = tree.space.measure(tree.bounds);
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const KdNode& node = tree.nodes[i];
    const KdNodeInfo& info = tree.info[i];
    s.max_depth = std::max(s.max_depth, int(info.depth));
    double p = root_area > 0.0 ? double(tree.space.measure(info.box)) / root_area : 1.0;
    if (node.is_leaf()) {
      ++s.leaves;
      if (node.prim_count() == 0) ++s.empty_leaves;
      s.max_leaf_prims = std::max<size_t>(s.max_leaf_prims, node.prim_count());
      s.sah_cost += p * double(options.t_i) * double(node.prim_count());
    } else {
      s.sah_cost += p * double(options.t_t);
    }
  }
  return s;
}

namespace kd {

Bounds3 clipped_bounds(const Geometry& geometry, uint32_t prim, const Bounds3& box) {
  if (geometry.type(prim) == PrimType::triangle)
    return without_negative_zero(clip_triangle_bounds(geometry.vertex(prim, 0), geometry.vertex(prim, 1),
                                                      geometry.vertex(prim, 2), box));
  return without_negative_zero(intersection_of(geometry.prim_bounds(prim), box));
}

Bounds3 straddler_bounds(const Geometry& geometry, uint32_t prim, const Bounds3& child) {
  Bounds3 b = clipped_bounds(geometry, prim, child);
  if (b.empty()) b = without_negative_zero(intersection_of(geometry.prim_bounds(prim), child));
  return b;
}

void straddler_bounds_split(const Geometry& geometry, uint32_t prim, const Bounds3& box, int axis,
                            float position, Bounds3* below, Bounds3* above) {
  Bounds3 below_box = box, above_box = box;
  below_box.hi[axis] = position;
  above_box.lo[axis] = position;
  if (geometry.type(prim) != PrimType::triangle) {
    *below = straddler_bounds(geometry, prim, below_box);
    *above = straddler_bounds(geometry, prim, above_box);
    return;
  }
  clip_triangle_bounds_split(geometry.vertex(prim, 0), geometry.vertex(prim, 1), geometry.vertex(prim, 2),
                             box, axis, position, below, above);
  *below = below->empty() ? intersection_of(geometry.prim_bounds(prim), below_box) : *below;
  *above = above->empty() ? intersection_of(geometry.prim_bounds(prim), above_box) : *above;
  *below = without_negative_zero(*below);
  *above = without_negative_zero(*above);
}

std::vector<PrimRef> root_prim_refs(const Geometry& geometry) {
  std::vector<PrimRef> prims(geometry.size());
  for (uint32_t id = 0; id < geometry.size(); ++id)
    prims[id] = {id, clipped_bounds(geometry, id, geometry.bounds())};
  return prims;
}

void classify_prim_refs(const Geometry& geometry, const std::vector<PrimRef>& prims, int axis, float position,
                        bool planar_below, const Bounds3& below_box, const Bounds3& above_box,
                        std::vector<PrimRef>* below, std::vector<PrimRef>* above) {
  for (const PrimRef& r : prims) {
    float lo = r.bounds.lo[axis], hi = r.bounds.hi[axis];
    if (lo == position && hi == position) {
      (planar_below ? below : above)->push_back(r);
    } else if (hi <= position) {
      below->push_back(r);
    } else if (lo >= position) {
      above->push_back(r);
    } else {  // straddles the plane: clipped again to each child
      below->push_back({r.prim, straddler_bounds(geometry, r.prim, below_box)});
      above->push_back({r.prim, straddler_bounds(geometry, r.prim, above_box)});
    }
  }
}

TreeWriter::TreeWriter(const Geometry& geometry, const KdOptions& options)
    : options_(options),
      model_{options.t_t, options.t_i, options.empty_bonus},
      max_depth_(kd_max_depth(options, geometry.size())),
      budget_(kd_reference_budget(options, geometry.size())) {
  tree_.bounds = geometry.bounds();
  tree_.space = geometry.split_space();
  // Reserved once: SAH trees of meshes have about 13 nodes per primitive (the bunny: 13.05), and the leaves
  // never hold more references than the budget; growing instead copied the arrays three times.
  const size_t n = geometry.size();
  tree_.nodes.reserve(14 * n + 1);
  tree_.info.reserve(14 * n + 1);
  tree_.prim_index.reserve(std::min(budget_, 8 * n));
}

uint32_t TreeWriter::add_node(const Bounds3& box, int32_t parent, int32_t depth) {
  if (tree_.nodes.size() >= KdNode::kMaxIndex)
    fail("more than " + std::to_string(KdNode::kMaxIndex) + " nodes");
  tree_.nodes.push_back(KdNode::make_leaf(0, 0));
  KdNodeInfo info;
  info.box = box;
  info.parent = parent;
  info.depth = depth;
  tree_.info.push_back(info);
  return uint32_t(tree_.nodes.size() - 1);
}

void TreeWriter::set_leaf(uint32_t node, const uint32_t* prims, uint32_t count, float cost) {
  if (tree_.prim_index.size() + count > KdNode::kMaxIndex)
    fail("more than " + std::to_string(KdNode::kMaxIndex) + " primitive references");
  tree_.nodes[node] = KdNode::make_leaf(uint32_t(tree_.prim_index.size()), count);
  tree_.prim_index.insert(tree_.prim_index.end(), prims, prims + count);
  tree_.info[node].cost = cost;
}

void TreeWriter::set_inner(uint32_t node, int axis, float split, uint32_t above_child) {
  tree_.nodes[node] = KdNode::make_inner(axis, split, above_child);
}

}  // namespace kd
}  // namespace raystep
