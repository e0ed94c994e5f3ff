// BVH construction: options, the recursive build over ranges of primitive references (the two subtrees as TBB
// tasks), the deterministic numbering of the nodes, the listener's replay, and the statistics of a built
// tree.
//
// Determinism: a subtree over n primitives has at most 2n - 1 nodes, so the subtree over refs[b, e) owns the
// 2(e - b) - 1 slots from its root's slot on: the root, then its left subtree's slots, then its right's.
// Every node's slot depends on the split decisions only, never on which thread ran first, and slot order is a
// depth-first preorder; the used slots, numbered in order, are the node ids. Reductions are min, max and
// integer sums; partitions run on one thread per node.
#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include "bvh_build_common.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, "bvh: " + what);
}

void validate(const Geometry& geometry, const BvhOptions& o) {
  if (o.builder != BvhBuilder::binned && o.builder != BvhBuilder::sweep && o.builder != BvhBuilder::median &&
      o.builder != BvhBuilder::sbvh)
    fail("unknown builder");
  if (!std::isfinite(o.spatial_alpha) || !(o.spatial_alpha >= 0.f))
    fail("spatial_alpha must be a finite number >= 0");
  if (!std::isfinite(o.spatial_budget) || !(o.spatial_budget >= 0.f) || o.spatial_budget > 16.f)
    fail("spatial_budget must be in 0..16");
  if (!std::isfinite(o.t_i) || !(o.t_i > 0.f)) fail("t_i must be a finite number > 0");
  if (!std::isfinite(o.t_t) || !(o.t_t >= 0.f)) fail("t_t must be a finite number >= 0");
  if (o.bins < 2 || o.bins > 256) fail("bins must be in 2..256");
  if (o.leaf_size < 1) fail("leaf_size must be at least 1");
  if (o.max_leaf_size < o.leaf_size) fail("max_leaf_size must be at least leaf_size");
  if (o.max_depth < 1 || o.max_depth > kBvhMaxDepth)
    fail("max_depth must be in 1.." + std::to_string(kBvhMaxDepth));
  if (o.threads < 0) fail("threads must be >= 0");
  if (geometry.size() > BvhNode::kMaxCount)
    fail("more than " + std::to_string(BvhNode::kMaxCount) + " primitives");
}


struct Slots {
  std::vector<BvhNode> nodes;
  std::vector<BvhNodeInfo> info;
  std::vector<uint8_t> used;
};

class Builder {
 public:
  Builder(const BvhOptions& o, SplitSpace space, bvh::PrimRef* refs, Slots& slots)
      : o_(o), space_(space), refs_(refs), slots_(slots) {}

  void build(uint32_t slot, uint32_t begin, uint32_t end, int depth, int32_t parent_slot) {
    using namespace bvh;
    const uint32_t n = end - begin;
    PrimRef* refs = refs_ + begin;
    Bounds3 box, centroids;
    range_bounds(refs, n, &box, &centroids);
    NodePlan plan = plan_node(refs, n, box, centroids, depth, o_, space_, nullptr);
    BvhNodeInfo& info = slots_.info[slot];
    info.parent = parent_slot;
    info.depth = depth;
    info.prims = n;
    slots_.used[slot] = 1;
    if (plan.leaf) {
      std::sort(refs, refs + n, [](const PrimRef& x, const PrimRef& y) { return x.id < y.id; });
      slots_.nodes[slot] = BvhNode::make_leaf(box, begin, n);
      info.cost = plan.leaf_cost;
      return;
    }
    uint32_t m = apply_split(refs, n, centroids, plan, o_);
    uint32_t left = slot + 1, right = slot + 2 * m;
    slots_.nodes[slot] = BvhNode::make_inner(box, plan.chosen.axis, right);
    info.cost = plan.chosen.cost;
    if (n >= kParallelPrims) {
      tbb::parallel_invoke([&] { build(left, begin, begin + m, depth + 1, int32_t(slot)); },
                           [&] { build(right, begin + m, end, depth + 1, int32_t(slot)); });
    } else {
      build(left, begin, begin + m, depth + 1, int32_t(slot));
      build(right, begin + m, end, depth + 1, int32_t(slot));
    }
  }

 private:
  const BvhOptions& o_;
  SplitSpace space_;
  bvh::PrimRef* refs_;
  Slots& slots_;
};

// The SBVH tells its listener (when given) itself; the others are replayed.
BvhData build(const Geometry& geometry, const BvhOptions& options, BvhBuildListener* sbvh_listener) {
  validate(geometry, options);
  const uint32_t n = uint32_t(geometry.size());
  BvhData out;
  out.space = geometry.split_space();
  if (n == 0) {
    out.nodes.push_back(BvhNode::make_leaf(Bounds3(), 0, 0));
    out.info.push_back(BvhNodeInfo{});
    return out;
  }
  if (options.builder == BvhBuilder::sbvh) return bvh::build_sbvh(geometry, options, sbvh_listener);
  std::vector<bvh::PrimRef> refs = bvh::make_refs(geometry);
  Slots slots;
  const size_t capacity = 2 * size_t(n) - 1;
  slots.nodes.resize(capacity);
  slots.info.resize(capacity);
  slots.used.assign(capacity, 0);
  Builder builder(options, out.space, refs.data(), slots);
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] { builder.build(0, 0, n, 0, -1); });

  // Number the used slots in order (a preorder), then move the nodes down to their ids.
  std::vector<uint32_t> id_of(capacity, 0);
  uint32_t count = 0;
  for (size_t s = 0; s < capacity; ++s)
    if (slots.used[s]) id_of[s] = count++;
  out.nodes.resize(count);
  out.info.resize(count);
  for (size_t s = 0; s < capacity; ++s) {
    if (!slots.used[s]) continue;
    uint32_t id = id_of[s];
    BvhNode node = slots.nodes[s];
    if (!node.is_leaf()) node.index = id_of[node.index];
    out.nodes[id] = node;
    BvhNodeInfo info = slots.info[s];
    if (info.parent >= 0) info.parent = int32_t(id_of[size_t(info.parent)]);
    out.info[id] = info;
  }
  out.prim_index.resize(n);
  for (uint32_t i = 0; i < n; ++i) out.prim_index[i] = refs[i].id;
  return out;
}

// Tells the listener about every node in id order, each decided again by plan_node from the node's own
// primitives (a subtree's primitives are contiguous in prim_index; the decision depends on the set, not its
// order), with candidates for the nodes it wants. The build itself stays free of listener calls, so that it
// can run in parallel and number its nodes at the end.
void replay(const Geometry& geometry, const BvhOptions& options, const BvhData& bvh,
            BvhBuildListener& listener) {
  const size_t count = bvh.nodes.size();
  std::vector<uint32_t> first(count, 0);
  for (size_t i = count; i-- > 0;)
    first[i] = bvh.nodes[i].is_leaf() ? bvh.nodes[i].first_prim() : first[i + 1];
  std::vector<bvh::PrimRef> refs;
  std::vector<BvhCandidate> candidates;
  for (size_t i = 0; i < count; ++i) {
    const BvhNodeInfo& info = bvh.info[i];
    refs.resize(info.prims);
    for (uint32_t k = 0; k < info.prims; ++k) {
      uint32_t id = bvh.prim_index[first[i] + k];
      refs[k] = {bvh::without_negative_zero(geometry.prim_bounds(id)), id};
    }
    Bounds3 box, centroids;
    bvh::range_bounds(refs.data(), info.prims, &box, &centroids);
    bool wants = listener.wants_candidates(uint32_t(i));
    candidates.clear();
    bvh::NodePlan plan = bvh::plan_node(refs.data(), info.prims, box, centroids, info.depth, options,
                                        bvh.space, wants ? &candidates : nullptr);
    for (const BvhCandidate& c : candidates) listener.candidate(uint32_t(i), c);
    if (plan.leaf)
      listener.leaf_made(uint32_t(i), bvh.nodes[i], info, plan.leaf_cost, plan.reason);
    else
      listener.split(uint32_t(i), bvh.nodes[i], info, plan.chosen, plan.leaf_cost);
  }
}

}  // namespace

namespace bvh {

std::vector<PrimRef> make_refs(const Geometry& geometry) {
  const uint32_t n = uint32_t(geometry.size());
  std::vector<PrimRef> refs(n);
  for (uint32_t id = 0; id < n; ++id) {
    Bounds3 b = geometry.prim_bounds(id);
    // Non-finite coordinates would break the bins and the sorts (and can never be hit).
    if (!is_finite(b.lo) || !is_finite(b.hi)) fail("primitive " + std::to_string(id) + " is not finite");
    refs[id] = {without_negative_zero(b), id};
  }
  return refs;
}

}  // namespace bvh

const char* bvh_leaf_reason_name(BvhLeafReason reason) {
  switch (reason) {
    case BvhLeafReason::few_primitives:
      return "few_primitives";
    case BvhLeafReason::max_depth:
      return "max_depth";
    case BvhLeafReason::no_cheaper_split:
      return "no_cheaper_split";
    case BvhLeafReason::no_candidate:
      return "no_candidate";
  }
  return "unknown";
}

BvhData build_bvh(const Geometry& geometry, const BvhOptions& options) {
  return build(geometry, options, nullptr);
}

BvhData build_bvh(const Geometry& geometry, const BvhOptions& options, BvhBuildListener& listener) {
  if (options.builder == BvhBuilder::sbvh) return build(geometry, options, &listener);
  BvhData bvh = build(geometry, options, nullptr);
  if (geometry.size() > 0) replay(geometry, options, bvh, listener);
  return bvh;
}

BvhStats bvh_stats(const BvhData& bvh, const BvhOptions& options) {
  BvhStats s;
  s.nodes = bvh.nodes.size();
  if (bvh.nodes.empty()) return s;
  const SplitSpace space = bvh.space;
  const double root_area = space.measure(bvh.nodes[0].box);
  auto weight = [&](const Bounds3& b) {
    return root_area > 0.0 ? double(space.measure(b)) / root_area : 1.0;
  };
  size_t leaf_prims = 0;
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNode& node = bvh.nodes[i];
    s.max_depth = std::max(s.max_depth, int(bvh.info[i].depth));
    double p = weight(node.box);
    if (node.is_leaf()) {
      ++s.leaves;
      leaf_prims += node.prim_count();
      s.max_leaf_prims = std::max<size_t>(s.max_leaf_prims, node.prim_count());
      s.sah_cost += p * double(options.t_i) * double(node.prim_count());
    } else {
      s.sah_cost += p * double(options.t_t);
      const Bounds3& l = bvh.nodes[i + 1].box;
      const Bounds3& r = bvh.nodes[node.second_child()].box;
      Bounds3 both;  // the intersection of the children's boxes
      both.lo = glm::max(l.lo, r.lo);
      both.hi = glm::min(l.hi, r.hi);
      double own = space.measure(node.box);
      if (!both.empty() && own > 0.0) s.overlap += p * double(space.measure(both)) / own;
    }
  }
  s.mean_leaf_prims = s.leaves ? double(leaf_prims) / double(s.leaves) : 0.0;
  s.references = leaf_prims;
  return s;
}

}  // namespace raystep
