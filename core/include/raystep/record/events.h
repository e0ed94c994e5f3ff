// The traversal events a recorder logs, one per step of the algorithm. The names are fixed (they are the
// trace format's contract with the GUI and with users' scripts): traces from any version read the same.
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "raystep/record/recorder.h"

namespace raystep {

enum class EventType : uint8_t {
  ray_begin,      // origin, direction, tmin, tmax, kind, depth, pixel (in TracedRay)
  cell,           // grid: i, j, k, t_enter, t_exit, tMax and tDelta per axis, the axis stepped next
  node,           // trees: node id, depth, t_min, t_max
  push,           // trees: the far child pushed with its interval
  pop,            // trees: an entry popped from the stack
  leaf,           // trees: a leaf reached
  prim_test,      // primitive id, hit or not, t
  mailbox_hit,    // primitive id skipped: already tested for this ray
  hit_deferred,   // a hit found in this cell but beyond its exit: kept, not yet accepted
  hit_accepted,   // primitive id, t, why now
  ray_end,        // the result and the ray's counters
  sah_candidate,  // build: a candidate split plane (kd-tree issue)
  split,          // build: the chosen split
  leaf_made,      // build: a node made a leaf
  box_test,       // BVH (version 3): a child's box tested: parent, node, depth, hit, t_near, t_far
  skip,           // BVH (version 3): a popped entry not visited, its t_near being beyond the nearest hit
};
constexpr int kEventTypeCount = 16;

const char* event_type_name(EventType type);
// False for an unknown name.
bool parse_event_type(const std::string& name, EventType* type);

const char* accept_reason_name(AcceptReason reason);
bool parse_accept_reason(const std::string& name, AcceptReason* reason);

// One event: the type and the fields that type uses (the others keep their defaults).
struct Event {
  uint32_t seq = 0;
  EventType type = EventType::ray_begin;
  // cell
  int cell[3] = {0, 0, 0};
  float t_enter = 0.f, t_exit = 0.f;
  glm::vec3 t_max{0.f}, t_delta{0.f};
  int next_axis = -1;  // -1: the walk ends in this cell
  // node, push, pop, leaf, skip; box_test: the child tested (node, its depth), t_min_node = t_near and
  // t_max_node = t_far on a hit, and the node it was tested from (parent)
  int32_t node = -1;
  int32_t depth = 0;
  float t_min_node = 0.f, t_max_node = 0.f;
  int32_t parent = -1;
  // prim_test, mailbox_hit, hit_deferred, hit_accepted, ray_end (prim -1: a miss); box_test: the box was hit
  int32_t prim = -1;
  bool hit = false;
  float t = 0.f;
  AcceptReason reason = AcceptReason::inside_cell;
};

// The counters of one ray, reported with ray_end.
struct RayCounters {
  uint32_t cells = 0, nodes = 0, prim_tests = 0, prim_hits = 0, mailbox_hits = 0, pushes = 0, pops = 0;
  uint32_t box_tests = 0;  // version 3: BVH child boxes tested
};

}  // namespace raystep
