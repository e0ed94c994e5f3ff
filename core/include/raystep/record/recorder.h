// Recorders: what a traversal kernel tells about its work. Every kernel takes the recorder as a template
// parameter. NullRecorder's members are empty and `enabled` is false, so the kernel compiles to the same code
// as one without hooks; CountingRecorder keeps per-ray counters (heat maps, statistics). Payloads that cost
// something to build are made only inside `if constexpr (Recorder::enabled)`.
#pragma once

#include <cstdint>
#include <type_traits>
#include <glm/vec3.hpp>

#include "raystep/geometry/ray.h"

namespace raystep {

struct Hit;

// One cell of the 3D-DDA (Amanatides and Woo): its index, the ray's interval inside it, and the DDA state.
struct GridCellStep {
  int i, j, k;
  float t_enter, t_exit;
  glm::vec3 t_max;    // t at which the ray crosses the next cell boundary on each axis
  glm::vec3 t_delta;  // t between successive boundaries on each axis (+inf: the ray does not move on it)
  int next_axis;      // the axis of the smallest t_max, stepped next (-1: the walk ends in this cell)
};

// A tree node on the walk (kd-tree, BVH): id, depth, and the ray's interval [t_min, t_max] inside it.
struct TreeStep {
  int32_t node;
  int32_t depth;
  float t_min, t_max;
};

// A BVH child's bounding box tested from its parent (lecture: "bounding volumes can overlap", so both children
// of a node may be entered): [t_near, t_far] where the ray is inside the box, or a miss. A wide BVH tests up to
// eight children at once and reports each.
struct BoxTest {
  int32_t parent;  // the node whose children are tested
  int32_t child;   // the child's node id
  int32_t depth;   // the child's depth
  bool hit;
  float t_near, t_far;  // meaningful on a hit
};

// Why a hit was accepted as the nearest.
enum class AcceptReason : uint8_t {
  inside_cell,     // the hit lies before the next cell's entry: "tmin(cell) > tmax(ray)"
  any_hit,         // a shadow ray: any hit will do
  structure_done,  // the walk left the structure with this hit as the nearest
  next_node_beyond,  // trees: the next node on the stack starts beyond the hit (its tmin > the hit's t)
};
constexpr int kAcceptReasonCount = 4;

struct NullRecorder {
  static constexpr bool enabled = false;
  void ray_begin(const Ray&) {}
  void cell(const GridCellStep&) {}
  void box_entered(uint32_t /*object*/, float /*t_enter*/) {}
  void node(const TreeStep&) {}  // an inner or leaf node visited
  void push(const TreeStep&) {}  // the far child pushed on the stack, with its interval
  void pop(const TreeStep&) {}   // an entry popped
  void leaf(const TreeStep&) {}  // a leaf reached: its primitives are tested next
  void box_test(const BoxTest&) {}  // BVH: a child's box tested
  void skip(const TreeStep&) {}  // BVH: a popped entry not visited, its t_near being beyond the nearest hit
  void prim_test(uint32_t /*prim*/, bool /*hit*/, float /*t*/) {}
  void volume_test(uint32_t /*object*/, bool /*hit*/) {}  // bvol: an object's bounding volume tested
  void volume_false_positive(uint32_t /*object*/) {}      // bvol: a volume entered, its object missed
  void mailbox_hit(uint32_t /*prim*/) {}
  void hit_deferred(uint32_t /*prim*/, float /*t*/, float /*t_cell_exit*/) {}
  void hit_accepted(uint32_t /*prim*/, float /*t*/, AcceptReason) {}
  void ray_end(const Hit&) {}
};

// Per-ray counters, summed over every ray traced with the same recorder.
struct CountingRecorder {
  static constexpr bool enabled = false;  // counters only: no event payloads are built
  uint64_t rays = 0, cells = 0, nodes = 0, leaves = 0, pushes = 0, pops = 0;
  uint64_t prim_tests = 0, prim_hits = 0, mailbox_hits = 0, deferred = 0;
  uint64_t box_tests = 0, skips = 0;
  uint64_t volume_tests = 0, volume_hits = 0, volume_false_positives = 0;  // bvol
  void ray_begin(const Ray&) { ++rays; }
  void cell(const GridCellStep&) { ++cells; }
  void box_entered(uint32_t, float) { ++nodes; }
  void node(const TreeStep&) { ++nodes; }
  void push(const TreeStep&) { ++pushes; }
  void pop(const TreeStep&) { ++pops; }
  void leaf(const TreeStep&) { ++leaves; }
  void box_test(const BoxTest&) { ++box_tests; }
  void skip(const TreeStep&) { ++skips; }
  void prim_test(uint32_t, bool hit, float) {
    ++prim_tests;
    prim_hits += hit;
  }
  void volume_test(uint32_t, bool hit) {
    ++volume_tests;
    volume_hits += hit;
  }
  void volume_false_positive(uint32_t) { ++volume_false_positives; }
  void mailbox_hit(uint32_t) { ++mailbox_hits; }
  void hit_deferred(uint32_t, float, float) { ++deferred; }
  void hit_accepted(uint32_t, float, AcceptReason) {}
  void ray_end(const Hit&) {}
};

// Whether a recorder reads the node ids of tree steps: every recorder but the null and the counting one. A walk
// whose hot data does not hold ids (the binary BVH's child pairs) looks them up in a cold table only for these.
template <class Recorder>
constexpr bool kReadsNodeIds =
    !std::is_same_v<Recorder, NullRecorder> && !std::is_same_v<Recorder, CountingRecorder>;

}  // namespace raystep
