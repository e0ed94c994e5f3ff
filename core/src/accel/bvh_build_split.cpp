// The BVH builders' split search, one function per algorithm (binned SAH, full sweep SAH, object median)
// behind the one decision per node of plan_node: leaf rules first, then the builder's best candidate, then
// the comparison with the leaf cost N t_i (which a node of more than max_leaf_size primitives may not take).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "bvh_build_common.h"

namespace raystep::bvh {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Bins of one axis: slot = floor((c - lo) * bins / extent), clamped to the last; an axis whose centroids do
// not spread (or spread over so little that bins / extent overflows) has no bins.
struct BinMap {
  float lo[3], scale[3];
  bool usable[3];
  int bins;
  BinMap(const Bounds3& centroids, int bins_) : bins(bins_) {
    for (int a = 0; a < 3; ++a) {
      float extent = centroids.hi[a] - centroids.lo[a];
      lo[a] = centroids.lo[a];
      scale[a] = extent > 0.f ? float(bins) / extent : 0.f;
      usable[a] = extent > 0.f && std::isfinite(scale[a]);
    }
  }
  int slot(const PrimRef& r, int a) const {
    float f = (r.centroid(a) - lo[a]) * scale[a];
    return f >= float(bins - 1) ? bins - 1 : int(f);
  }
};

// Per-bin boxes and counts for three axes; combined by union and sum, exact whatever the order. In place (no
// allocation per node): only the first 3 * bins slots are used, initialised and copied.
constexpr int kMaxBins = 256;
struct BinSet {
  int bins;
  Bounds3 box[3 * kMaxBins];     // [axis * bins + slot]
  uint32_t count[3 * kMaxBins];  // [axis * bins + slot]
  explicit BinSet(int b) : bins(b) { std::fill(count, count + 3 * b, 0u); }
  BinSet(const BinSet& o) : bins(o.bins) {
    std::copy(o.box, o.box + 3 * bins, box);
    std::copy(o.count, o.count + 3 * bins, count);
  }
  BinSet& operator=(const BinSet& o) {
    bins = o.bins;
    std::copy(o.box, o.box + 3 * bins, box);
    std::copy(o.count, o.count + 3 * bins, count);
    return *this;
  }
  void add(const PrimRef* refs, size_t begin, size_t end, const BinMap& map) {
    for (size_t i = begin; i < end; ++i)
      for (int a = 0; a < 3; ++a) {
        if (!map.usable[a]) continue;
        size_t k = size_t(a * bins + map.slot(refs[i], a));
        box[k].extend(refs[i].box);
        ++count[k];
      }
  }
  void merge(const BinSet& o) {
    for (int k = 0; k < 3 * bins; ++k) {
      box[k].extend(o.box[k]);
      count[k] += o.count[k];
    }
  }
};

// Binned SAH (Wald 2007): bin the centroids, sweep the bin boundaries from both ends. Candidate `bin` b puts
// slots 0..b on the left.
bool best_binned(const PrimRef* refs, uint32_t n, const Bounds3& box, const Bounds3& centroids,
                 const BvhOptions& o, SplitSpace space, std::vector<BvhCandidate>* out, BvhCandidate* best) {
  const int bins = o.bins;
  BinMap map(centroids, bins);
  // The bins live on the stack (about 20 kB; the recursion does not hold them); big nodes are binned in
  // parallel chunks, each with its own.
  BinSet set(bins);
  if (n >= kParallelPrims) {
    set = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 8192), BinSet(bins),
        [&](const tbb::blocked_range<size_t>& r, BinSet s) {
          s.add(refs, r.begin(), r.end(), map);
          return s;
        },
        [](BinSet a, const BinSet& b) {
          a.merge(b);
          return a;
        });
  } else {
    set.add(refs, 0, n, map);
  }
  const float area_node = space.measure(box);
  bool found = false;
  float planes[256];
  for (int a = 0; a < space.axes; ++a) {
    if (!map.usable[a]) continue;
    for (int b = 0; b + 1 < bins; ++b) planes[b] = map.lo[a] + float(b + 1) / map.scale[a];
    // Each primitive counts on the left of every boundary after its slot, on the right of every one before.
    const uint32_t* counts = &set.count[a * bins];
    found = sweep_bins(&set.box[a * bins], counts, counts, planes, bins, a, false, area_node, o, space, out, best,
                       found);
  }
  return found;
}

bool centroid_less(const PrimRef& x, const PrimRef& y, int a) {
  float cx = x.centroid(a), cy = y.centroid(a);
  return cx < cy || (cx == cy && x.id < y.id);
}

// Full sweep SAH: on each axis sort by centroid (ties by id) and evaluate every boundary between neighbours.
// Candidate `bin` i puts sorted positions 0..i on the left.
bool best_sweep(const PrimRef* refs, uint32_t n, const Bounds3& box, const Bounds3& centroids,
                const BvhOptions& o, SplitSpace space, std::vector<BvhCandidate>* out, BvhCandidate* best) {
  thread_local std::vector<PrimRef> sorted;
  thread_local std::vector<float> right_area;
  sorted.assign(refs, refs + n);
  right_area.resize(n);
  const float area_node = space.measure(box);
  bool found = false;
  for (int a = 0; a < space.axes; ++a) {
    if (!(centroids.hi[a] > centroids.lo[a])) continue;  // as the binned builder: an axis without spread
    std::sort(sorted.begin(), sorted.end(),
              [a](const PrimRef& x, const PrimRef& y) { return centroid_less(x, y, a); });
    Bounds3 acc;
    for (uint32_t i = n - 1; i > 0; --i) {
      acc.extend(sorted[i].box);
      right_area[i - 1] = space.measure(acc);
    }
    Bounds3 left;
    for (uint32_t i = 0; i + 1 < n; ++i) {
      left.extend(sorted[i].box);
      BvhCandidate c;
      c.axis = a;
      c.bin = int(i);
      c.position = 0.5f * (sorted[i].centroid(a) + sorted[i + 1].centroid(a));
      c.n_left = i + 1;
      c.n_right = n - i - 1;
      c.area_left = space.measure(left);
      c.area_right = right_area[i];
      c.area_node = area_node;
      c.cost = split_cost(o, area_node, c.n_left, c.area_left, c.n_right, c.area_right);
      if (out) out->push_back(c);
      if (!found || c.cost < best->cost) {
        *best = c;
        found = true;
      }
    }
  }
  return found;
}

// Object median: the longest axis of the centroids' box, the lower half of the centroids (ties by id) left.
BvhCandidate median_split(const PrimRef* refs, uint32_t n, const Bounds3& box, const Bounds3& centroids,
                          const BvhOptions& o, SplitSpace space) {
  thread_local std::vector<PrimRef> sorted;
  sorted.assign(refs, refs + n);
  int a = space.longest_axis(centroids);
  uint32_t m = n / 2;
  std::nth_element(sorted.begin(), sorted.begin() + m, sorted.end(),
                   [a](const PrimRef& x, const PrimRef& y) { return centroid_less(x, y, a); });
  Bounds3 left, right;
  for (uint32_t i = 0; i < m; ++i) left.extend(sorted[i].box);
  for (uint32_t i = m; i < n; ++i) right.extend(sorted[i].box);
  BvhCandidate c;
  c.axis = a;
  c.bin = int(m) - 1;
  c.position = sorted[m].centroid(a);
  c.n_left = m;
  c.n_right = n - m;
  c.area_left = space.measure(left);
  c.area_right = space.measure(right);
  c.area_node = space.measure(box);
  c.cost = split_cost(o, c.area_node, m, c.area_left, n - m, c.area_right);
  return c;
}

// All centroids at one point: no plane separates them, so the ids are halved (the lower ids left).
BvhCandidate forced_split(const PrimRef* refs, uint32_t n, const Bounds3& box, const Bounds3& centroids,
                          const BvhOptions& o, SplitSpace space) {
  thread_local std::vector<PrimRef> sorted;
  sorted.assign(refs, refs + n);
  uint32_t m = n / 2;
  std::nth_element(sorted.begin(), sorted.begin() + m, sorted.end(),
                   [](const PrimRef& x, const PrimRef& y) { return x.id < y.id; });
  Bounds3 left, right;
  for (uint32_t i = 0; i < m; ++i) left.extend(sorted[i].box);
  for (uint32_t i = m; i < n; ++i) right.extend(sorted[i].box);
  BvhCandidate c;
  c.axis = space.longest_axis(box);
  c.bin = int(m) - 1;
  c.position = centroids.lo[c.axis];
  c.n_left = m;
  c.n_right = n - m;
  c.area_left = space.measure(left);
  c.area_right = space.measure(right);
  c.area_node = space.measure(box);
  c.cost = split_cost(o, c.area_node, m, c.area_left, n - m, c.area_right);
  return c;
}

}  // namespace

bool sweep_bins(const Bounds3* box, const uint32_t* enter, const uint32_t* leave, const float* planes, int bins,
                int axis, bool spatial, float area_node, const BvhOptions& o, SplitSpace space,
                std::vector<BvhCandidate>* out, BvhCandidate* best, bool found) {
  // Sweep from the right: what lies in bins b+1.. .
  float right_area[kMaxSweepBins];
  uint32_t right_count[kMaxSweepBins];
  Bounds3 acc;
  uint32_t cnt = 0;
  for (int b = bins - 1; b > 0; --b) {
    acc.extend(box[b]);
    cnt += leave[b];
    right_area[b - 1] = space.measure(acc);
    right_count[b - 1] = cnt;
  }
  // Sweep from the left, evaluating each boundary.
  Bounds3 left;
  uint32_t n_left = 0;
  for (int b = 0; b + 1 < bins; ++b) {
    left.extend(box[b]);
    n_left += enter[b];
    BvhCandidate c;
    c.spatial = spatial;
    c.axis = axis;
    c.bin = b;
    c.position = planes[b];
    c.n_left = n_left;
    c.n_right = right_count[b];
    c.area_left = space.measure(left);
    c.area_right = right_area[b];
    c.area_node = area_node;
    c.cost = split_cost(o, area_node, c.n_left, c.area_left, c.n_right, c.area_right);
    if (out) out->push_back(c);
    // Only a boundary with primitives on both sides is a split; the first lowest cost wins (lower axis, bin).
    if (c.n_left > 0 && c.n_right > 0 && (!found || c.cost < best->cost)) {
      *best = c;
      found = true;
    }
  }
  return found;
}

float split_cost(const BvhOptions& o, float area_node, uint32_t n_l, float area_l, uint32_t n_r,
                 float area_r) {
  if (!(area_node > 0.f)) return o.t_t + o.t_i * float(n_l + n_r);
  return o.t_t + o.t_i * (area_l * float(n_l) + area_r * float(n_r)) / area_node;
}

void range_bounds(const PrimRef* refs, uint32_t n, Bounds3* box, Bounds3* centroids) {
  using Pair = std::pair<Bounds3, Bounds3>;
  auto add = [refs](size_t begin, size_t end, Pair p) {
    for (size_t i = begin; i < end; ++i) {
      p.first.extend(refs[i].box);
      p.second.extend(0.5f * (refs[i].box.lo + refs[i].box.hi));
    }
    return p;
  };
  Pair p;
  if (n >= kParallelPrims) {
    p = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n, 4096), Pair{},
        [&](const tbb::blocked_range<size_t>& r, Pair acc) { return add(r.begin(), r.end(), acc); },
        [](Pair a, const Pair& b) {
          a.first.extend(b.first);
          a.second.extend(b.second);
          return a;
        });
  } else {
    p = add(0, n, p);
  }
  *box = p.first;
  *centroids = p.second;
}

NodePlan plan_node(const PrimRef* refs, uint32_t n, const Bounds3& box, const Bounds3& centroids, int depth,
                   const BvhOptions& o, SplitSpace space, std::vector<BvhCandidate>* candidates) {
  NodePlan plan;
  plan.leaf_cost = o.t_i * float(n);
  if (n <= uint32_t(o.leaf_size)) {
    plan.reason = BvhLeafReason::few_primitives;
    return plan;
  }
  if (depth >= o.max_depth) {
    plan.reason = BvhLeafReason::max_depth;
    return plan;
  }
  bool spread = false;
  for (int a = 0; a < space.axes; ++a) spread |= centroids.hi[a] > centroids.lo[a];
  BvhCandidate best;
  bool found = false;
  if (spread) {
    switch (o.builder) {
      case BvhBuilder::sweep:
        found = best_sweep(refs, n, box, centroids, o, space, candidates, &best);
        break;
      case BvhBuilder::median:
        best = median_split(refs, n, box, centroids, o, space);
        if (candidates) candidates->push_back(best);
        found = true;
        break;
      case BvhBuilder::binned:
      default:
        found = best_binned(refs, n, box, centroids, o, space, candidates, &best);
        break;
    }
  }
  if (!found) {
    // No plane separates the centroids: a leaf while that is allowed, else the id range halved.
    if (n <= uint32_t(o.max_leaf_size)) {
      plan.reason = BvhLeafReason::no_candidate;
      return plan;
    }
    best = forced_split(refs, n, box, centroids, o, space);
    if (candidates) candidates->push_back(best);
    plan.forced = true;
  } else if (o.builder != BvhBuilder::median && !(best.cost < plan.leaf_cost) &&
             n <= uint32_t(o.max_leaf_size)) {
    // The median builder splits whenever it can (leaves by size and depth only): the contrast to the SAH.
    plan.reason = BvhLeafReason::no_cheaper_split;
    return plan;
  }
  plan.leaf = false;
  plan.chosen = best;
  plan.chosen.chosen = true;
  if (candidates)
    for (BvhCandidate& c : *candidates)
      if (c.axis == best.axis && c.bin == best.bin && c.spatial == best.spatial) c.chosen = true;
  return plan;
}

uint32_t apply_split(PrimRef* refs, uint32_t n, const Bounds3& centroids, const NodePlan& plan,
                     const BvhOptions& o) {
  const BvhCandidate& c = plan.chosen;
  const int a = c.axis;
  if (plan.forced) {
    std::nth_element(refs, refs + c.n_left, refs + n,
                     [](const PrimRef& x, const PrimRef& y) { return x.id < y.id; });
  } else if (o.builder == BvhBuilder::binned) {
    BinMap map(centroids, o.bins);
    std::partition(refs, refs + n, [&](const PrimRef& r) { return map.slot(r, a) <= c.bin; });
  } else {
    // Sweep and median: the n_left smallest by (centroid, id), the order their candidates were counted in.
    std::nth_element(refs, refs + c.n_left, refs + n,
                     [a](const PrimRef& x, const PrimRef& y) { return centroid_less(x, y, a); });
  }
  return c.n_left;
}

}  // namespace raystep::bvh
