// What a BVH walk does at the current inner node, for the replay: each child's box test, the child entered
// first and the ones pushed for later (lecture: tight bounding volumes that may overlap).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/replay/replay_state.h"

namespace raystep::replay {

// BVH: one child's box tested from the current inner node (lecture: "bounding volumes can overlap", so the
// ray may enter more than one child). done: the test is at or before the current event.
struct BoxTestMark {
  int32_t child = -1;
  bool hit = false;
  float t_near = 0.f, t_far = 0.f;  // on a hit
  int event = -1;
  bool done = false;
};

// BVH: what the walk does at the current inner node: each child's box test ([t_near, t_far] or a miss), the
// child entered first (the nearer one hit) and the children pushed for later, from the events that follow the
// node event.
struct BvhChoice {
  bool valid = false;  // false: the current node is not an inner BVH node with box tests
  int node_event = -1;
  int32_t node = -1;
  std::vector<BoxTestMark> tests;  // in the order the kernel tested them
  int32_t first = -1;              // the child walked next (-1: none hit, the walk pops)
  std::vector<int32_t> pushed;     // pushed, bottom first
  bool decided = false;            // the current event is the last box test or later: the choice is known
};

// True when the ray walked a BVH: the trace's structure is a BVH ("bvh", "bvh-sweep", "bvh-median", "bvh4",
// "bvh8"), or (without a trace) its events test children's boxes.
bool is_bvh_kind(const std::string& kind);
bool is_bvh_ray(const Trace* trace, const TracedRay& ray);
// The BVH choice at the current inner node (the node event of s.node_event).
BvhChoice bvh_choice(const TracedRay& ray, const ReplayState& s);

}  // namespace raystep::replay
