// The O(N log N) SAH kd-tree build of Wald and Havran ("On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)", 2006): the events of every primitive (where its clipped bounds start and end on
// each axis, or where it lies if it is planar) are sorted once at the root; each node finds its best plane by
// one sweep per axis over its sorted events, then hands its events to its children in order, sorting only the
// new events of the primitives that straddle the plane. Same decisions as kdtree_build_reference.cpp.
#include <algorithm>
#include <vector>

#include "kdtree_build_common.h"

namespace raystep::kd {
namespace {

// The paper's event types, in its order at equal positions: end (-), planar (|), start (+).
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

// One event on one axis. The type sits above the primitive id in `key`, so that ordering by (position, key) is
// the paper's order by (position, type), made total by the id.
struct Event {
  float position;
  uint32_t key;

  static Event make(float position, EventType type, uint32_t prim) {
    return Event{position, (uint32_t(type) << 30) | prim};
  }
  EventType type() const { return EventType(key >> 30); }
  uint32_t prim() const { return key & KdNode::kMaxIndex; }
  bool operator<(const Event& e) const { return position < e.position || (position == e.position && key < e.key); }
};

// The events of a primitive with bounds b, appended to one list per axis.
void append_events(const Bounds3& b, uint32_t prim, std::vector<Event>* lists) {
  for (int a = 0; a < 3; ++a) {
    if (b.lo[a] == b.hi[a]) {
      lists[a].push_back(Event::make(b.lo[a], kPlanar, prim));
    } else {
      lists[a].push_back(Event::make(b.lo[a], kStart, prim));
      lists[a].push_back(Event::make(b.hi[a], kEnd, prim));
    }
  }
}

// Where a primitive goes when its node is split (the paper's classification).
enum class Side : uint8_t { both, below, above };

// A node's events: on each axis the range [begin, end) of that axis's arena. The arenas are stacks: the node
// being built is on top, the above siblings still waiting for their turn lie under it.
struct NodeEvents {
  size_t begin[3], end[3];
  uint32_t n_prims;
};

template <class Recorder>
class SweepBuilder {
 public:
  SweepBuilder(const Geometry& geometry, const KdOptions& options, Recorder& rec)
      : geometry_(geometry), out_(geometry, options), rec_(rec) {}

  KdTreeData build() {
    // The root's events, sorted once per axis: the only full sort of the build.
    const Bounds3 box = geometry_.bounds();
    const uint32_t n = uint32_t(geometry_.size());
    NodeEvents root;
    for (int a = 0; a < 3; ++a) events_[a].reserve(2 * size_t(n) + 16);
    for (uint32_t id = 0; id < n; ++id) append_events(clipped_bounds(geometry_, id, box), id, events_);
    for (int a = 0; a < 3; ++a) {
      std::sort(events_[a].begin(), events_[a].end());
      root.begin[a] = 0;
      root.end[a] = events_[a].size();
    }
    root.n_prims = n;
    side_.assign(n, Side::both);
    build_node(box, -1, 0, out_.root_budget(), root);
    return out_.finish();
  }

 private:
  void make_leaf(uint32_t node, const NodeEvents& ev, float leaf_cost, LeafReason reason) {
    // Each primitive of the node has exactly one start or planar event on every axis: take them from x.
    leaf_prims_.clear();
    for (size_t i = ev.begin[0]; i < ev.end[0]; ++i)
      if (events_[0][i].type() != kEnd) leaf_prims_.push_back(events_[0][i].prim());
    std::sort(leaf_prims_.begin(), leaf_prims_.end());
    out_.set_leaf(node, leaf_prims_.data(), uint32_t(leaf_prims_.size()), leaf_cost);
    rec_.leaf_made(node, out_.info(node), ev.n_prims, leaf_cost, reason);
  }

  // The sweep (the paper's FindPlane): per axis, walk the sorted events one distinct position at a time,
  // keeping N_L (primitives reaching below the plane), N_P (lying in it) and N_R (reaching above).
  bool find_plane(uint32_t node, const Bounds3& box, const NodeEvents& ev, SahCandidate* best) {
    bool record = false;
    if constexpr (Recorder::enabled) record = rec_.wants_candidates(node);
    const SahModel& model = out_.model();
    const float area_node = box.surface_area();
    if (!(area_node > 0.f)) return false;  // a segment or a point: no ray can tell the children apart
    bool found = false;
    for (int axis = 0; axis < 3; ++axis) {
      const SplitAreas areas(box, axis);
      const Event* e = events_[axis].data() + ev.begin[axis];
      const size_t count = ev.end[axis] - ev.begin[axis];
      uint32_t n_left = 0, n_right = ev.n_prims;
      for (size_t i = 0; i < count;) {
        // p-, p|, p+: how many events of each type lie at this position.
        const float position = e[i].position;
        uint32_t at[3] = {0, 0, 0};  // indexed by EventType
        do {
          ++at[e[i].type()];
          ++i;
        } while (i < count && e[i].position == position);
        const uint32_t ends = at[kEnd], planars = at[kPlanar], starts = at[kStart];
        // Move the plane onto p: N_P = p|, N_R -= p| + p-; evaluate; then N_L += p+ + p|.
        n_right -= planars + ends;
        if (box.lo[axis] < position && position < box.hi[axis]) {
          SahCandidate c = model.candidate(areas, position, n_left, n_right, planars);
          if constexpr (Recorder::enabled)
            if (record) rec_.sah_candidate(node, c);
          if (!found || cheaper(c, *best)) {
            *best = c;
            found = true;
          }
        }
        n_left += starts + planars;
      }
    }
    return found;
  }

  // Hand the node's events to its children (the paper's split step), keeping them sorted.
  void split_events(const NodeEvents& ev, const SahCandidate& plane, const Bounds3& below_box,
                    const Bounds3& above_box, NodeEvents* below, NodeEvents* above) {
    const int k = plane.axis;
    const float p = plane.position;

    // 1. Classify by one pass over the split axis's events: a start at or after p means above only, an end at
    //    or before p below only, anything else both; planar ones by their position and the chosen side.
    for (size_t i = ev.begin[k]; i < ev.end[k]; ++i) {
      const Event& e = events_[k][i];
      switch (e.type()) {
        case kStart:
          side_[e.prim()] = e.position >= p ? Side::above : Side::both;
          break;
        case kEnd:
          if (e.position <= p) side_[e.prim()] = Side::below;
          break;
        case kPlanar:
          side_[e.prim()] =
              (e.position < p || (e.position == p && plane.planar_below)) ? Side::below : Side::above;
          break;
      }
    }

    // 2. The straddling primitives are clipped again to each child; their new events are sorted (few).
    for (int a = 0; a < 3; ++a) {
      new_below_[a].clear();
      new_above_[a].clear();
    }
    for (size_t i = ev.begin[k]; i < ev.end[k]; ++i) {
      const Event& e = events_[k][i];
      if (e.type() != kStart || side_[e.prim()] != Side::both) continue;
      append_events(straddler_bounds(geometry_, e.prim(), below_box), e.prim(), new_below_);
      append_events(straddler_bounds(geometry_, e.prim(), above_box), e.prim(), new_above_);
    }

    // 3. The primitives on one side keep their events, spliced out in order; 4. merged with the new ones. The
    //    above child goes to the arena first, the below child on top of it (it is built first).
    for (int a = 0; a < 3; ++a) {
      std::sort(new_below_[a].begin(), new_below_[a].end());
      std::sort(new_above_[a].begin(), new_above_[a].end());
      kept_below_.clear();
      kept_above_.clear();
      for (size_t i = ev.begin[a]; i < ev.end[a]; ++i) {
        const Event& e = events_[a][i];
        Side s = side_[e.prim()];
        if (s == Side::below) kept_below_.push_back(e);
        else if (s == Side::above) kept_above_.push_back(e);
      }
      const size_t base = ev.begin[a];
      const size_t n_above = kept_above_.size() + new_above_[a].size();
      const size_t n_below = kept_below_.size() + new_below_[a].size();
      if (events_[a].size() < base + n_above + n_below) events_[a].resize(base + n_above + n_below);
      auto out = events_[a].begin() + base;
      out = std::merge(kept_above_.begin(), kept_above_.end(), new_above_[a].begin(), new_above_[a].end(), out);
      std::merge(kept_below_.begin(), kept_below_.end(), new_below_[a].begin(), new_below_[a].end(), out);
      above->begin[a] = base;
      above->end[a] = base + n_above;
      below->begin[a] = base + n_above;
      below->end[a] = base + n_above + n_below;
    }
    below->n_prims = plane.n_below;
    above->n_prims = plane.n_above;
  }

  void build_node(const Bounds3& box, int32_t parent, int32_t depth, size_t budget, const NodeEvents& ev) {
    const uint32_t node = out_.add_node(box, parent, depth);
    const uint32_t n = ev.n_prims;
    const float leaf_cost = out_.model().leaf_cost(n);

    // 1. Leaves made without a search.
    if (n <= uint32_t(out_.options().leaf_size)) return make_leaf(node, ev, leaf_cost, LeafReason::few_primitives);
    if (depth >= out_.max_depth()) return make_leaf(node, ev, leaf_cost, LeafReason::max_depth);

    // 2. The best plane by the sweep; 3. leaves decided by it.
    SahCandidate best;
    if (!find_plane(node, box, ev, &best)) return make_leaf(node, ev, leaf_cost, LeafReason::no_candidate);
    if (!(best.cost < leaf_cost)) return make_leaf(node, ev, leaf_cost, LeafReason::no_cheaper_split);
    if (!budget_allows(budget, best.n_below, best.n_above)) return make_leaf(node, ev, leaf_cost, LeafReason::budget);

    // 4. Split the events, then build below, then above (depth-first preorder).
    out_.set_split_cost(node, best.cost);
    rec_.split(node, out_.info(node), n, best.axis, best.position, best.cost, leaf_cost);
    Bounds3 below_box = box, above_box = box;
    below_box.hi[best.axis] = best.position;
    above_box.lo[best.axis] = best.position;
    NodeEvents below, above;
    split_events(ev, best, below_box, above_box, &below, &above);
    const BudgetShare share = share_budget(budget, best.n_below, best.n_above);
    build_node(below_box, int32_t(node), depth + 1, share.below, below);
    uint32_t above_child = out_.node_count();
    build_node(above_box, int32_t(node), depth + 1, share.above, above);
    out_.set_inner(node, best.axis, best.position, above_child);
  }

  const Geometry& geometry_;
  TreeWriter out_;
  Recorder& rec_;
  std::vector<Event> events_[3];  // one arena per axis
  std::vector<Side> side_;        // per primitive, valid for the node being split
  // Scratch reused by every node: no allocation per node once they have grown.
  std::vector<Event> new_below_[3], new_above_[3], kept_below_, kept_above_;
  std::vector<uint32_t> leaf_prims_;
};

}  // namespace

template <class Recorder>
KdTreeData build_sah(const Geometry& geometry, const KdOptions& options, Recorder& rec) {
  return SweepBuilder<Recorder>(geometry, options, rec).build();
}

template KdTreeData build_sah(const Geometry&, const KdOptions&, NullBuildRecorder&);
template KdTreeData build_sah(const Geometry&, const KdOptions&, BuildListenerRecorder&);

}  // namespace raystep::kd
