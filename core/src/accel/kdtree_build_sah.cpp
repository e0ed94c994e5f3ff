// The O(N log N) SAH kd-tree build of Wald and Havran ("On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)", 2006): the events of every primitive (where its clipped bounds start and end on
// each axis, or where it lies if it is planar) are sorted once at the root; each node finds its best plane by
// one sweep per axis over its sorted events, then hands its events to its children in order, sorting only the
// new events of the primitives that straddle the plane. Same decisions as kdtree_build_reference.cpp.
#include <algorithm>
#include <vector>

#include "kdtree_build_common.h"
#include "raystep/geometry/numerics.h"

namespace raystep::kd {
namespace {

// The paper's event types, in its order at equal positions: end (-), planar (|), start (+).
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

// One event on one axis, packed in 64 bits so that events sort and merge as integers: above, the position's
// bits made order-preserving; below, the key, the type above the primitive id. Ordering the packed bits is
// the paper's order by (position, type), made total by the id. (Positions are finite and never -0, see
// kd::clipped_bounds, so equal positions are equal bits.)
struct Event {
  uint64_t bits;

  static Event make(float position, EventType type, uint32_t prim) {
    return Event{(uint64_t(ordered_bits(position)) << 32) | (uint64_t(type) << 30) | prim};
  }
  float position() const { return from_ordered_bits(position_bits()); }
  uint32_t position_bits() const { return uint32_t(bits >> 32); }
  EventType type() const { return EventType((bits >> 30) & 3u); }
  uint32_t prim() const { return uint32_t(bits) & KdNode::kMaxIndex; }
  // (position, type): the same for all the events one step of the sweep counts together.
  uint64_t group() const { return bits >> 30; }
  bool operator<(const Event& e) const { return bits < e.bits; }

  // A float's bits as an unsigned integer in the order of the floats: the sign bit flipped for positive
  // numbers, every bit for negative ones.
  static uint32_t ordered_bits(float f) {
    const uint32_t u = float_to_bits(f);
    return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
  }
  static float from_ordered_bits(uint32_t o) {
    return bits_to_float((o & 0x80000000u) ? (o & 0x7fffffffu) : ~o);
  }
};

// The merge of two sorted runs of distinct events into out; returns the end of the output.
inline Event* merge_events(const Event* a, const Event* a_end, const Event* b, const Event* b_end,
                           Event* out) {
  while (a != a_end && b != b_end) {
    const bool take_b = b->bits < a->bits;
    *out++ = take_b ? *b : *a;
    b += take_b;
    a += !take_b;
  }
  out = std::copy(a, a_end, out);
  return std::copy(b, b_end, out);
}

// The same in place, for a run a[0, n_a) that begins the output: a[0, n_a + n_b) gets the merge, written from
// the back, so that no event of a is overwritten before it is read.
inline void merge_events_in_place(Event* a, size_t n_a, const Event* b, size_t n_b) {
  size_t i = n_a, j = n_b, w = n_a + n_b;
  while (i > 0 && j > 0) {
    const bool take_a = b[j - 1].bits < a[i - 1].bits;
    a[--w] = take_a ? a[i - 1] : b[j - 1];
    i -= take_a;
    j -= !take_a;
  }
  while (j > 0) a[--w] = b[--j];  // what is left of a is in place already
}

// The events of a primitive with bounds b, written at out[a] on each axis a (each pointer moves past them; a
// primitive has at most two events per axis).
inline void append_events(const Bounds3& b, uint32_t prim, Event** out) {
  for (int a = 0; a < 3; ++a) {
    if (b.lo[a] == b.hi[a]) {
      *out[a]++ = Event::make(b.lo[a], kPlanar, prim);
    } else {
      *out[a]++ = Event::make(b.lo[a], kStart, prim);
      *out[a]++ = Event::make(b.hi[a], kEnd, prim);
    }
  }
}

// Room for n primitives' events in each of three lists, and the pointers where to write them. The lists only
// grow (no zeroing of the room again for every node); what was written ends at the pointers.
inline void make_room(std::vector<Event>* lists, size_t n, Event** out) {
  for (int a = 0; a < 3; ++a) {
    if (lists[a].size() < 2 * n) lists[a].resize(std::max(2 * n, 2 * lists[a].size()));
    out[a] = lists[a].data();
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
    // The arenas grow to a few times the root's events (the waiting above siblings); reserved once.
    for (int a = 0; a < 3; ++a) events_[a].reserve(8 * size_t(n) + 16);
    Event* out[3];
    make_room(events_, n, out);
    for (uint32_t id = 0; id < n; ++id) append_events(clipped_bounds(geometry_, id, box), id, out);
    for (int a = 0; a < 3; ++a) {
      std::sort(events_[a].data(), out[a]);
      root.begin[a] = 0;
      root.end[a] = size_t(out[a] - events_[a].data());
    }
    root.n_prims = n;
    side_.assign(n, Side::both);
    build_node(box, -1, 0, out_.root_budget(), root);
    return out_.finish();
  }

 private:
  void make_leaf(uint32_t node, const NodeEvents& ev, float leaf_cost, LeafReason reason) {
    // Each primitive of the node has exactly one start or planar event on every axis: take them from x.
    // (Written and counted without a branch: the types come in random order.)
    if (leaf_prims_.size() < ev.end[0] - ev.begin[0]) leaf_prims_.resize(ev.end[0] - ev.begin[0]);
    size_t n = 0;
    for (size_t i = ev.begin[0]; i < ev.end[0]; ++i) {
      leaf_prims_[n] = events_[0][i].prim();
      n += events_[0][i].type() != kEnd;
    }
    std::sort(leaf_prims_.begin(), leaf_prims_.begin() + ptrdiff_t(n));
    out_.set_leaf(node, leaf_prims_.data(), uint32_t(n), leaf_cost);
    rec_.leaf_made(node, out_.info(node), ev.n_prims, leaf_cost, reason);
  }

  // The sweep (the paper's FindPlane): per axis, walk the sorted events one distinct position at a time,
  // keeping N_L (primitives reaching below the plane), N_P (lying in it) and N_R (reaching above).
  bool find_plane(uint32_t node, const Bounds3& box, const NodeEvents& ev, SahCandidate* best) {
    bool record = false;
    if constexpr (Recorder::enabled) record = rec_.wants_candidates(node);
    const SahModel& model = out_.model();
    const float area_node = out_.space().measure(box);
    if (!(area_node > 0.f)) return false;  // a segment or a point: no ray can tell the children apart
    // A lower bound on a candidate's cost, cheap to compute (a reciprocal for the divisions, and the largest
    // bonus): a candidate whose bound is not below the best cost cannot be strictly cheaper, so its exact
    // cost is not needed (unless the recorder wants it). The bound's slack of 2^-16 relative, and a little
    // absolute, is far beyond the rounding of either computation, so the tree is the same.
    const float inv_area_node = 1.f / area_node;
    const float bound_scale = (1.f - model.empty_bonus) * model.t_i;
    // Only where the bound's products stay finite (neither huge boxes times many primitives nor boxes so
    // small that 1 / area overflows): else every candidate is evaluated exactly.
    const bool may_skip = std::isfinite(inv_area_node) && area_node * float(ev.n_prims) < 1e37f;
    const bool packed_counts = ev.n_prims < (1u << 21);
    constexpr uint64_t kCountMask = (uint64_t(1) << 21) - 1;
    bool found = false;
    for (int axis = 0; axis < out_.space().axes; ++axis) {
      const SplitMeasure areas(box, axis, out_.space());
      const Event* e = events_[axis].data() + ev.begin[axis];
      const size_t count = ev.end[axis] - ev.begin[axis];
      // The node's interior on this axis as ordered bits (positions are never -0; the box's faces are made +0
      // so that comparing bits is comparing floats).
      const uint32_t lo_bits = Event::ordered_bits(box.lo[axis] + 0.f),
                     hi_bits = Event::ordered_bits(box.hi[axis] + 0.f);
      uint32_t n_left = 0, n_right = ev.n_prims;
      for (size_t i = 0; i < count;) {
        // p-, p|, p+: how many events of each type lie at this position (counted without branches on the
        // type: in three 21-bit fields of one integer while fewer primitives than 2^21 cannot overflow them).
        const uint32_t at_position = e[i].position_bits();
        uint32_t ends = 0, planars = 0, starts = 0;
        if (packed_counts) {
          uint64_t counts = 0;
          do {
            counts += uint64_t(1) << (21 * e[i].type());
            ++i;
          } while (i < count && e[i].position_bits() == at_position);
          ends = uint32_t(counts & kCountMask);
          planars = uint32_t((counts >> 21) & kCountMask);
          starts = uint32_t(counts >> 42);
        } else {
          do {
            const EventType type = e[i].type();
            ends += type == kEnd;
            planars += type == kPlanar;
            starts += type == kStart;
            ++i;
          } while (i < count && e[i].position_bits() == at_position);
        }
        // Move the plane onto p: N_P = p|, N_R -= p| + p-; evaluate; then N_L += p+ + p|.
        n_right -= planars + ends;
        if (lo_bits < at_position && at_position < hi_bits) {
          const float position = Event::from_ordered_bits(at_position);
          bool evaluate = !found || record || !may_skip;
          if (!evaluate) {
            const float a_below = areas.below(position), a_above = areas.above(position);
            const float weighted = (a_below * float(n_left) + a_above * float(n_right) +
                                    std::min(a_below, a_above) * float(planars)) *
                                   inv_area_node;
            const float bound = (model.t_t + bound_scale * weighted) * (1.f - 1.f / 65536.f) - 1e-30f;
            evaluate = !(bound >= best->cost);
          }
          if (evaluate) {
            SahCandidate c = model.candidate(areas, position, n_left, n_right, planars);
            if constexpr (Recorder::enabled)
              if (record) rec_.sah_candidate(node, c);
            if (!found || cheaper(c, *best)) {
              *best = c;
              found = true;
            }
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
    //    or before p below only, anything else both; planar ones by their position and the chosen side. The
    //    straddlers are collected in the same pass: an end after p of a primitive whose start was before it.
    //    (Their order does not matter: their new events are sorted.)
    const uint32_t p_bits =
        Event::ordered_bits(p);  // p is an event's position: comparing bits is comparing floats
    if (straddlers_.size() < ev.end[k] - ev.begin[k]) straddlers_.resize(ev.end[k] - ev.begin[k]);
    size_t n_straddlers = 0;
    for (size_t i = ev.begin[k]; i < ev.end[k];
         ++i) {  // selects, not branches: the types come in random order
      const Event& e = events_[k][i];
      const uint32_t x = e.position_bits();
      const EventType type = e.type();
      const uint32_t prim = e.prim();
      Side& side = side_[prim];
      const Side start_side = x >= p_bits ? Side::above : Side::both;
      const Side planar_side =
          (x < p_bits || (x == p_bits && plane.planar_below)) ? Side::below : Side::above;
      const Side end_side = x <= p_bits ? Side::below : side;
      straddlers_[n_straddlers] = prim;
      n_straddlers += type == kEnd && x > p_bits && side == Side::both;
      side = type == kStart ? start_side : (type == kPlanar ? planar_side : end_side);
    }

    // 2. The straddling primitives are clipped again to each child; their new events are sorted (few).
    Event *below_out[3], *above_out[3];
    make_room(new_below_, n_straddlers, below_out);
    make_room(new_above_, n_straddlers, above_out);
    Bounds3 box = below_box;
    box.hi[k] = above_box.hi[k];
    for (size_t i = 0; i < n_straddlers; ++i) {
      // The triangles are scattered in memory: ask for the vertices a few clips ahead.
      if (i + kPrefetchAhead < n_straddlers &&
          geometry_.type(straddlers_[i + kPrefetchAhead]) == PrimType::triangle)
        __builtin_prefetch(&geometry_.vertex(straddlers_[i + kPrefetchAhead], 0));
      const uint32_t prim = straddlers_[i];
      Bounds3 below_bounds, above_bounds;
      straddler_bounds_split(geometry_, prim, box, k, p, &below_bounds, &above_bounds);
      append_events(below_bounds, prim, below_out);
      append_events(above_bounds, prim, above_out);
    }

    // 3. The primitives on one side keep their events, spliced out in order: the above ones moved down in
    // place
    //    (never past where they are read), the below ones to scratch; 4. merged with the new ones. The above
    //    child goes to the arena first, the below child on top of it (it is built first).
    for (int a = 0; a < 3; ++a) {
      const Event *new_below = new_below_[a].data(), *new_above = new_above_[a].data();
      const size_t n_new_below = size_t(below_out[a] - new_below),
                   n_new_above = size_t(above_out[a] - new_above);
      std::sort(new_below_[a].data(), below_out[a]);
      std::sort(new_above_[a].data(), above_out[a]);
      const size_t base = ev.begin[a], count = ev.end[a] - ev.begin[a];
      const size_t most = base + count + n_new_above + n_new_below;
      if (events_[a].size() < most) events_[a].resize(most);
      if (kept_below_.size() < count) kept_below_.resize(count);
      Event* e = events_[a].data() + base;
      size_t n_kept_above = 0, n_kept_below = 0;
      for (size_t i = 0; i < count; ++i) {  // without branches: the sides of successive events are random
        const Event x = e[i];
        const Side s = side_[x.prim()];
        e[n_kept_above] = x;  // n_kept_above <= i: already read
        kept_below_[n_kept_below] = x;
        n_kept_above += s == Side::above;
        n_kept_below += s == Side::below;
      }
      const size_t n_above = n_kept_above + n_new_above;
      const size_t n_below = n_kept_below + n_new_below;
      merge_events_in_place(e, n_kept_above, new_above, n_new_above);
      merge_events(kept_below_.data(), kept_below_.data() + n_kept_below, new_below, new_below + n_new_below,
                   e + n_above);
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
    if (n <= uint32_t(out_.options().leaf_size))
      return make_leaf(node, ev, leaf_cost, LeafReason::few_primitives);
    if (depth >= out_.max_depth()) return make_leaf(node, ev, leaf_cost, LeafReason::max_depth);

    // 2. The best plane by the sweep; 3. leaves decided by it.
    SahCandidate best;
    if (!find_plane(node, box, ev, &best)) return make_leaf(node, ev, leaf_cost, LeafReason::no_candidate);
    if (!(best.cost < leaf_cost)) return make_leaf(node, ev, leaf_cost, LeafReason::no_cheaper_split);
    if (!budget_allows(budget, best.n_below, best.n_above))
      return make_leaf(node, ev, leaf_cost, LeafReason::budget);

    // 4. Split the events, then build below, then above (depth-first preorder).
    out_.set_split_cost(node, best.cost);
    rec_.split(node, out_.info(node), n, best.axis, best.position, best.cost, leaf_cost);
    Bounds3 below_box = box, above_box = box;
    below_box.hi[best.axis] = best.position;
    above_box.lo[best.axis] = best.position;
    NodeEvents below, above;
    split_events(ev, best, below_box, above_box, &below, &above);
    uint32_t above_child = build_children(
        out_, budget, best.n_below, best.n_above,
        [&](size_t b) { build_node(below_box, int32_t(node), depth + 1, b, below); },
        [&](size_t b) { build_node(above_box, int32_t(node), depth + 1, b, above); });
    out_.set_inner(node, best.axis, best.position, above_child);
  }

  const Geometry& geometry_;
  TreeWriter out_;
  Recorder& rec_;
  std::vector<Event> events_[3];  // one arena per axis
  std::vector<Side> side_;        // per primitive, valid for the node being split
  // Scratch reused by every node: no allocation per node once they have grown.
  std::vector<Event> new_below_[3], new_above_[3], kept_below_;
  std::vector<uint32_t> leaf_prims_, straddlers_;
  static constexpr size_t kPrefetchAhead = 4;
};

}  // namespace

template <class Recorder>
KdTreeData build_sah(const Geometry& geometry, const KdOptions& options, Recorder& rec) {
  return SweepBuilder<Recorder>(geometry, options, rec).build();
}

template KdTreeData build_sah(const Geometry&, const KdOptions&, NullBuildRecorder&);
template KdTreeData build_sah(const Geometry&, const KdOptions&, BuildListenerRecorder&);

}  // namespace raystep::kd
