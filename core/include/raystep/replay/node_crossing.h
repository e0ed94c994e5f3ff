// What the walk does at a kd-tree's or a BSP tree's inner node, for the replay: t*, the near and far children
// and which of them the events visit, as the lecture's stack traversal decides (Intersect(near, t_min, t*),
// the far child (t*, t_max) pushed).
#pragma once

#include <cstdint>

#include "raystep/replay/replay_state.h"

namespace raystep::replay {

// Trees: what the ray does at an inner node, in the lecture's words. t* is where the ray meets the split
// plane; the near child is the side the ray comes from as it moves along its direction (below the plane when
// the direction points up the axis, by the sign bit, as the kernel decides). Then only the near child is
// visited (t* > t_max: the ray leaves the node first), only the far one (t* < t_min: the node's part of the
// ray lies beyond the plane), or both: Intersect(near, t_min, t*) now and the far child (t*, t_max) pushed.
enum class Crossing { near_only, far_only, both, in_plane };
const char* crossing_name(Crossing c);
struct NodeCrossing {
  bool valid = false;  // false: no inner node now, or its split plane is not in the trace
  int node_event = -1;
  int32_t node = -1;
  int axis = 0;
  float split = 0.f;
  float t_star = 0.f;  // NaN when the ray lies in the plane, +-inf when it runs parallel to it
  float t_min = 0.f, t_max = 0.f;
  bool near_is_below = true;  // the near child is the one below the plane
  Crossing crossing = Crossing::near_only;
  int32_t near_child = -1, far_child = -1;  // -1: not visited from this node
  // A general BSP node (trace version 4): the plane dot(normal, p) = offset instead of axis and split. t* =
  // (offset - n.o) / (n.dir), by the kernel's bsp_crossing (double, with its error bound: [t_lo, t_hi] holds
  // the exact t*); origin_side = n.o - offset (the origin's signed distance for a unit normal), n_dot_dir =
  // n.dir. Crossing::in_plane then means "parallel within rounding and on or too near the plane to tell".
  bool general = false;
  glm::vec3 normal{0.f};
  float offset = 0.f;
  double origin_side = 0.0, n_dot_dir = 0.0;
  float t_lo = 0.f, t_hi = 0.f;
};

// The node of a trace's geometry with this id, or null.
const TraceNode* find_node(const Trace& trace, int32_t id);
// The crossing at the current inner node (the node event of s.node_event), from the trace's split plane and
// the events that follow it.
NodeCrossing node_crossing(const Trace& trace, const TracedRay& ray, const ReplayState& s);

}  // namespace raystep::replay
