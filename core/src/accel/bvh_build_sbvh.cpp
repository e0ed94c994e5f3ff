// The spatial-split BVH (Stich, Friedrich and Dietrich, "Spatial splits in bounding volume hierarchies",
// HPG 2009). At each node the builder weighs two kinds of split by the same SAH cost:
//   - the object split of the binned builder (plan_node): each reference goes to one side, the two boxes
//     are tight around their references and may overlap;
//   - where those boxes overlap by more than alpha of the root's measure, a spatial split: the node's box is
//     cut into bins along each axis, every reference is clipped into each bin it crosses, and a candidate
//     plane between bins sends a reference crossing it to both sides, each with only its part's box. The
//     children's boxes then meet at the plane and do not overlap, at the price of references.
// A reference that crosses the chosen plane is kept whole on one side when that costs less than cutting it
// ("reference unsplitting", section 4.4). References are ids with a box: the primitive clipped to the
// region of its node, rounded outward, so every point of a primitive lies in the box of some leaf that lists
// it and the walk, which tests the whole primitive, finds every hit the brute force finds.
//
// Determinism and threads: a node's two subtrees are built as tasks into their own node lists, numbered from
// 0 in depth-first preorder, and appended after the node, so the ids are a preorder whatever ran first. With
// a listener the build runs on one thread (the same tree) and its own decisions are told, in id order, at the
// end.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include "bvh_build_common.h"
#include "raystep/util/error.h"

namespace raystep::bvh {

namespace {

// Bins per axis of the spatial split search (Stich et al. use as many as the object binning).
constexpr int kSpatialBins = 16;

// Where the edge a-b crosses the plane x_axis = p (a and b strictly on either side), as a box that contains
// the true point. In float, t = (p - a) / (b - a) and a + t (b - a) carry at most 4 u (|a| + |b|) of rounding
// error (u = 2^-24: three roundings in t's and the product's factors, one in the sum), so the point is
// widened by twice that (FLT_EPSILON = 2u), plus the smallest normal float for underflow, and kept between a
// and b: a bound that scales with the vertices, not a fixed epsilon.
Bounds3 crossing(const glm::vec3& a, const glm::vec3& b, int axis, float p) {
  const float t = (p - a[axis]) / (b[axis] - a[axis]);
  Bounds3 q;
  for (int k = 0; k < 3; ++k) {
    if (k == axis) {
      q.lo[k] = q.hi[k] = p;
      continue;
    }
    const float x = a[k] + t * (b[k] - a[k]);
    const float err =
        4.f * FLT_EPSILON * (std::fabs(a[k]) + std::fabs(b[k])) + std::numeric_limits<float>::min();
    q.lo[k] = std::max(x - err, std::min(a[k], b[k]));
    q.hi[k] = std::min(x + err, std::max(a[k], b[k]));
  }
  return q;
}

Bounds3 intersection(const Bounds3& a, const Bounds3& b) {
  Bounds3 r;
  r.lo = glm::max(a.lo, b.lo);
  r.hi = glm::min(a.hi, b.hi);
  return r;
}

// The boxes of reference r's parts on either side of the plane x_axis = p: a triangle clipped exactly (its
// vertices on each side and its edges' crossings), a sphere by its box; each part within r's box and its
// side of the plane. A part that is empty there has an empty box: the primitive does not reach that side
// within r's region.
void split_reference(const Geometry& g, const PrimRef& r, int axis, float p, Bounds3* left, Bounds3* right) {
  Bounds3 l, h;
  if (g.type(r.id) == PrimType::triangle) {
    for (int i = 0; i < 3; ++i) {
      const glm::vec3& a = g.vertex(r.id, i);
      const glm::vec3& b = g.vertex(r.id, (i + 1) % 3);
      if (a[axis] <= p) l.extend(a);
      if (a[axis] >= p) h.extend(a);
      if ((a[axis] < p && b[axis] > p) || (a[axis] > p && b[axis] < p)) {
        const Bounds3 q = crossing(a, b, axis, p);
        l.extend(q);
        h.extend(q);
      }
    }
  } else {
    l = h = r.box;
  }
  l = intersection(l, r.box);
  h = intersection(h, r.box);
  l.hi[axis] = std::min(l.hi[axis], p);
  h.lo[axis] = std::max(h.lo[axis], p);
  *left = l;
  *right = h;
}

// Adds the parts of reference r between planes e and x + 1 on axis a (bins e..x, e < x) to their bins. A
// triangle's part in a slab is bounded by its vertices in the slab and its cross-sections at the slab's two
// planes, so each plane's cross-section is computed once; the first and last bins reach as far as r's box.
// The same boxes, bin by bin, as cutting r plane after plane with split_reference.
void chop_into_bins(const Geometry& g, const PrimRef& r, int a, const float* planes, int e, int x,
                    Bounds3* bins) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const bool triangle = g.type(r.id) == PrimType::triangle;
  glm::vec3 v[3];
  if (triangle)
    for (int k = 0; k < 3; ++k) v[k] = g.vertex(r.id, k);
  auto section = [&](float p) {  // where the triangle's edges cross the plane at p
    Bounds3 c;
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& u = v[k];
      const glm::vec3& w = v[(k + 1) % 3];
      if ((u[a] < p && w[a] > p) || (u[a] > p && w[a] < p)) c.extend(crossing(u, w, a, p));
    }
    return c;
  };
  Bounds3 low_cut;  // the cross-section at the bin's low plane
  for (int i = e; i <= x; ++i) {
    const float lo = i > e ? planes[i] : -kInf, hi = i < x ? planes[i + 1] : kInf;
    Bounds3 part = r.box;
    if (triangle) {
      const Bounds3 high_cut = i < x ? section(hi) : Bounds3();
      part = union_of(low_cut, high_cut);
      for (int k = 0; k < 3; ++k)
        if (v[k][a] >= lo && v[k][a] <= hi) part.extend(v[k]);
      part = intersection(part, r.box);
      low_cut = high_cut;
    }
    part.lo[a] = std::max(part.lo[a], lo);
    part.hi[a] = std::min(part.hi[a], hi);
    if (!part.empty()) bins[i].extend(part);
  }
}

// Which side of the plane at `p` a reference belongs to: left when it reaches below the plane (a reference
// flat in the plane counts as left), right when it reaches above it; both when it crosses. The bins count
// with the same comparisons, so a candidate's counts are what the split makes.
bool goes_left(const PrimRef& r, int a, float p) {
  return r.box.lo[a] < r.box.hi[a] ? r.box.lo[a] < p : r.box.lo[a] <= p;
}
bool goes_right(const PrimRef& r, int a, float p) {
  return r.box.hi[a] > p;
}

// The bin boundaries of one axis: planes[k] for k = 1..bins-1 cut the node's box into `bins` equal slabs
// (planes[0] unused). False when the box is too thin on the axis for strictly increasing planes.
bool spatial_planes(const Bounds3& box, int a, float* planes) {
  const float lo = box.lo[a], hi = box.hi[a];
  if (!(hi > lo)) return false;
  float prev = lo;
  for (int k = 1; k < kSpatialBins; ++k) {
    planes[k] = lo + (hi - lo) * (float(k) / float(kSpatialBins));
    if (!(planes[k] > prev) || !(planes[k] < hi)) return false;
    prev = planes[k];
  }
  return true;
}

// The best spatial split of refs[0..n): for each axis, each reference enters the bin of its low end and
// leaves from the bin of its high end (counted by the comparisons of goes_left / goes_right), and adds its
// clipped part to every bin between. Candidate `bin` b is the plane planes[b + 1], bins 0..b left.
bool best_spatial(const Geometry& g, const PrimRef* refs, uint32_t n, const Bounds3& box,
                  const BvhOptions& o, SplitSpace space, std::vector<BvhCandidate>* out, BvhCandidate* best) {
  const float area_node = space.measure(box);
  bool found = false;
  float planes[kSpatialBins];
  for (int a = 0; a < space.axes; ++a) {
    if (!spatial_planes(box, a, planes)) continue;
    Bounds3 bin_box[kSpatialBins];
    uint32_t enter[kSpatialBins] = {}, leave[kSpatialBins] = {};
    const float* first = planes + 1;
    const float* last = planes + kSpatialBins;
    for (uint32_t i = 0; i < n; ++i) {
      const PrimRef& r = refs[i];
      // enter: the planes the reference does not reach below (goes_left false); leave: the planes it
      // reaches above (goes_right true).
      const bool flat = !(r.box.lo[a] < r.box.hi[a]);
      const int e = int((flat ? std::lower_bound(first, last, r.box.lo[a])
                              : std::upper_bound(first, last, r.box.lo[a])) -
                        first);
      const int x = int(std::lower_bound(first, last, r.box.hi[a]) - first);
      ++enter[e];
      ++leave[x];
      if (e == x)
        bin_box[e].extend(r.box);
      else
        chop_into_bins(g, r, a, planes, e, x, bin_box);
    }
    found = sweep_bins(bin_box, enter, leave, planes + 1, kSpatialBins, a, true, area_node, o, space, out, best,
                       found);
  }
  return found;
}

// Splits refs at the spatial candidate c into *left and *right. A crossing reference is cut in two, or kept
// whole on the side where that lowers S_l N_l + S_r N_r (never emptying the other side).
void apply_spatial(const Geometry& g, const std::vector<PrimRef>& refs, const BvhCandidate& c, SplitSpace space,
                   std::vector<PrimRef>* left, std::vector<PrimRef>* right) {
  const int a = c.axis;
  const float p = c.position;
  Bounds3 lbox, rbox;
  uint32_t nl = 0, nr = 0;
  for (const PrimRef& r : refs) {
    const bool l = goes_left(r, a, p), h = goes_right(r, a, p);
    if (l && !h) lbox.extend(r.box), ++nl;
    if (h && !l) rbox.extend(r.box), ++nr;
  }
  // The crossing references' parts, as the bins saw them.
  for (const PrimRef& r : refs) {
    if (!(goes_left(r, a, p) && goes_right(r, a, p))) continue;
    Bounds3 below, above;
    split_reference(g, r, a, p, &below, &above);
    lbox.extend(below);
    rbox.extend(above);
    ++nl, ++nr;
  }
  left->clear();
  right->clear();
  for (const PrimRef& r : refs) {
    const bool l = goes_left(r, a, p), h = goes_right(r, a, p);
    if (!(l && h)) {
      (l ? left : right)->push_back(r);
      continue;
    }
    Bounds3 below, above;
    split_reference(g, r, a, p, &below, &above);
    if (below.empty() || above.empty()) {  // the primitive does not reach one side within its region
      if (!below.empty()) left->push_back({below, r.id}), --nr;
      if (!above.empty()) right->push_back({above, r.id}), --nl;
      continue;
    }
    const double cut = double(space.measure(lbox)) * nl + double(space.measure(rbox)) * nr;
    const double all_left =
        nr > 1 ? double(space.measure(union_of(lbox, r.box))) * nl + double(space.measure(rbox)) * (nr - 1)
               : cut + 1.0;
    const double all_right =
        nl > 1 ? double(space.measure(lbox)) * (nl - 1) + double(space.measure(union_of(rbox, r.box))) * nr
               : cut + 1.0;
    if (all_left < cut && all_left <= all_right) {
      left->push_back(r);
      lbox.extend(r.box);
      --nr;
    } else if (all_right < cut) {
      right->push_back(r);
      rbox.extend(r.box);
      --nl;
    } else {
      left->push_back({below, r.id});
      right->push_back({above, r.id});
    }
  }
}

// One node's decision, kept for the listener.
struct Decision {
  NodePlan plan;
  std::vector<BvhCandidate> candidates;
};

// A subtree in preorder, ids from 0 (its root).
struct Subtree {
  std::vector<BvhNode> nodes;
  std::vector<BvhNodeInfo> info;
  std::vector<uint32_t> prims;
  std::vector<Decision> decisions;  // one per node when there is a listener

  // Appends `o` as the children of the node at `parent`.
  void append(Subtree&& o, uint32_t parent) {
    const uint32_t node_offset = uint32_t(nodes.size()), prim_offset = uint32_t(prims.size());
    for (size_t i = 0; i < o.nodes.size(); ++i) {
      BvhNode n = o.nodes[i];
      n.index += n.is_leaf() ? prim_offset : node_offset;
      nodes.push_back(n);
      BvhNodeInfo inf = o.info[i];
      inf.parent = inf.parent < 0 ? int32_t(parent) : inf.parent + int32_t(node_offset);
      info.push_back(inf);
    }
    prims.insert(prims.end(), o.prims.begin(), o.prims.end());
    for (Decision& d : o.decisions) decisions.push_back(std::move(d));
  }
};

class SbvhBuilder {
 public:
  // With a listener the build runs on one thread into one list, so a node's id is known when it is made
  // and the listener can be asked whether it wants the node's candidates.
  SbvhBuilder(const Geometry& g, const BvhOptions& o, SplitSpace space, float root_measure,
              BvhBuildListener* listener)
      : g_(g), o_(o), space_(space), root_measure_(root_measure), listener_(listener) {
    object_ = o;
    object_.builder = BvhBuilder::binned;
  }

  // Builds refs (consumed) into `out` as a subtree whose root is out's next node; `parent` is that root's
  // parent in out (-1: none). `budget` is how many more references this subtree may make by cutting.
  void build(Subtree& out, std::vector<PrimRef>& refs, int depth, int32_t parent, uint64_t budget) {
    const uint32_t n = uint32_t(refs.size());
    const uint32_t self = uint32_t(out.nodes.size());
    Bounds3 box, centroids;
    range_bounds(refs.data(), n, &box, &centroids);
    out.nodes.emplace_back();
    out.info.push_back(BvhNodeInfo{parent, depth, n, 0.f});
    Decision d;
    std::vector<BvhCandidate>* cands =
        listener_ && listener_->wants_candidates(self) ? &d.candidates : nullptr;
    NodePlan plan = plan_node(refs.data(), n, box, centroids, depth, object_, space_, cands);

    std::vector<PrimRef> left, right;
    bool split = false;
    const bool by_rule = plan.leaf && (plan.reason == BvhLeafReason::few_primitives ||
                                       plan.reason == BvhLeafReason::max_depth);
    if (!plan.leaf) {
      const uint32_t m = apply_split(refs.data(), n, centroids, plan, object_);
      left.assign(refs.begin(), refs.begin() + m);
      right.assign(refs.begin() + m, refs.end());
      split = true;
    }
    if (!by_rule && budget > 0 && (plan.leaf || overlap(left, right) > o_.spatial_alpha * root_measure_)) {
      BvhCandidate s;
      std::vector<BvhCandidate> spatial;
      if (best_spatial(g_, refs.data(), n, box, o_, space_, cands ? &spatial : nullptr, &s) &&
          uint64_t(s.n_left) + s.n_right - n <= budget &&
          s.cost < (plan.leaf ? plan.leaf_cost : plan.chosen.cost)) {
        std::vector<PrimRef> l2, r2;
        apply_spatial(g_, refs, s, space_, &l2, &r2);
        if (!l2.empty() && !r2.empty()) {
          left.swap(l2);
          right.swap(r2);
          plan.leaf = false;
          plan.forced = false;
          s.chosen = true;
          plan.chosen = s;
          split = true;
          for (BvhCandidate& c : d.candidates) c.chosen = false;
          for (BvhCandidate& c : spatial) c.chosen = c.axis == s.axis && c.bin == s.bin;
        }
      }
      d.candidates.insert(d.candidates.end(), spatial.begin(), spatial.end());
    }
    if (!split) {
      std::sort(refs.begin(), refs.end(), [](const PrimRef& x, const PrimRef& y) { return x.id < y.id; });
      out.nodes[self] = BvhNode::make_leaf(box, uint32_t(out.prims.size()), n);
      for (const PrimRef& r : refs) out.prims.push_back(r.id);
      out.info[self].cost = plan.leaf_cost;
    } else {
      out.info[self].cost = plan.chosen.cost;
    }
    plan.leaf = !split;
    if (listener_) {
      d.plan = plan;
      out.decisions.push_back(std::move(d));
    }
    if (!split) return;
    std::vector<PrimRef>().swap(refs);

    const uint64_t made = left.size() + right.size() - n;
    const uint64_t rest = budget - std::min(budget, made);
    const uint64_t left_budget = rest * left.size() / (left.size() + right.size());
    const uint64_t right_budget = rest - left_budget;
    if (n >= kParallelPrims && !listener_) {
      Subtree a, b;
      tbb::parallel_invoke([&] { build(a, left, depth + 1, -1, left_budget); },
                           [&] { build(b, right, depth + 1, -1, right_budget); });
      out.append(std::move(a), self);
      out.nodes[self] = BvhNode::make_inner(box, plan.chosen.axis, uint32_t(out.nodes.size()));
      out.append(std::move(b), self);
    } else {
      build(out, left, depth + 1, int32_t(self), left_budget);
      out.nodes[self] = BvhNode::make_inner(box, plan.chosen.axis, uint32_t(out.nodes.size()));
      build(out, right, depth + 1, int32_t(self), right_budget);
    }
  }

 private:
  // The measure of the intersection of the two sides' boxes.
  float overlap(const std::vector<PrimRef>& l, const std::vector<PrimRef>& r) const {
    Bounds3 a, b;
    for (const PrimRef& x : l) a.extend(x.box);
    for (const PrimRef& x : r) b.extend(x.box);
    const Bounds3 both = intersection(a, b);
    return both.empty() ? 0.f : space_.measure(both);
  }

  const Geometry& g_;
  const BvhOptions& o_;
  BvhOptions object_;
  SplitSpace space_;
  float root_measure_;
  BvhBuildListener* listener_;
};

}  // namespace

BvhData build_sbvh(const Geometry& geometry, const BvhOptions& options, BvhBuildListener* listener) {
  BvhData out;
  out.space = geometry.split_space();
  std::vector<PrimRef> refs = make_refs(geometry);
  const uint32_t n = uint32_t(refs.size());
  Bounds3 box, centroids;
  range_bounds(refs.data(), n, &box, &centroids);
  const double budget = std::floor(double(options.spatial_budget) * double(n));
  // References are counted in 32 bits (BvhNode): the budget never lets them pass that.
  const uint64_t room = uint64_t(BvhNode::kMaxCount) - n;
  SbvhBuilder builder(geometry, options, out.space, out.space.measure(box), listener);
  Subtree tree;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] { builder.build(tree, refs, 0, -1, std::min<uint64_t>(uint64_t(budget), room)); });
  out.nodes = std::move(tree.nodes);
  out.info = std::move(tree.info);
  out.prim_index = std::move(tree.prims);
  if (listener) {
    for (size_t i = 0; i < out.nodes.size(); ++i) {
      const Decision& d = tree.decisions[i];
      for (const BvhCandidate& c : d.candidates) listener->candidate(uint32_t(i), c);
      if (d.plan.leaf)
        listener->leaf_made(uint32_t(i), out.nodes[i], out.info[i], d.plan.leaf_cost, d.plan.reason);
      else
        listener->split(uint32_t(i), out.nodes[i], out.info[i], d.plan.chosen, d.plan.leaf_cost);
    }
  }
  return out;
}

}  // namespace raystep::bvh
