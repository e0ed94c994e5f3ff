#include "raystep/replay/node_crossing.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "raystep/accel/bsp.h"
#include "raystep/geometry/numerics.h"

namespace raystep::replay {

const char* crossing_name(Crossing c) {
  switch (c) {
    case Crossing::near_only:
      return "near child only";
    case Crossing::far_only:
      return "far child only";
    case Crossing::both:
      return "both children";
    case Crossing::in_plane:
      return "both children (the ray lies in the plane)";
  }
  return "";
}

const TraceNode* find_node(const Trace& trace, int32_t id) {
  // The trace lists its nodes by id; fall back to a scan for a file written otherwise.
  auto it = std::lower_bound(trace.nodes.begin(), trace.nodes.end(), id,
                             [](const TraceNode& n, int32_t v) { return n.id < v; });
  if (it != trace.nodes.end() && it->id == id) return &*it;
  for (const TraceNode& n : trace.nodes)
    if (n.id == id) return &n;
  return nullptr;
}

namespace {

// A general BSP node: the plane's crossing as the kernel (bsp.h) decides it, and the children the events
// show.
NodeCrossing bsp_crossing(const TraceNode& n, const TracedRay& ray, const ReplayState& s, NodeCrossing c) {
  const std::vector<Event>& ev = ray.events;
  const Event& e = ev[size_t(s.node_event)];
  size_t next = size_t(s.node_event) + 1;
  c.general = true;
  c.normal = n.normal;
  c.offset = n.offset;
  c.t_min = e.t_min_node;
  c.t_max = e.t_max_node;
  const glm::vec3 o = ray.ray.origin, d = ray.ray.direction;
  c.origin_side = double(n.normal.x) * o.x + double(n.normal.y) * o.y + double(n.normal.z) * o.z - n.offset;
  c.n_dot_dir = double(n.normal.x) * d.x + double(n.normal.y) * d.y + double(n.normal.z) * d.z;
  const BspCrossing k =
      bsp_crossing(BspPlane{n.normal, n.offset}, o, d, std::max(std::fabs(c.t_min), std::fabs(c.t_max)));
  // The near child is the side the ray starts in (the slides'); on the plane, the side the ray moves into.
  c.near_is_below = c.origin_side < 0 ? true : c.origin_side > 0 ? false : k.below_first;
  c.t_lo = k.t_lo;
  c.t_hi = k.t_hi;
  if (k.kind == BspCrossing::crosses)
    c.t_star = float(-c.origin_side / c.n_dot_dir);
  else if (k.kind == BspCrossing::stays)
    c.t_star = k.below_first == (c.n_dot_dir >= 0.0) ? kInfinity : -kInfinity;  // never reached, or behind
  else
    c.t_star = std::numeric_limits<float>::quiet_NaN();
  if (next >= ev.size()) return c;
  if (ev[next].type == EventType::push) {
    c.crossing = k.kind == BspCrossing::undecided ? Crossing::in_plane : Crossing::both;
    c.near_is_below = k.below_first;  // both visited: the near one is the first (the origin's side, or on the
                                      // plane within rounding the side the ray moves into)
    c.far_child = ev[next].node;
    if (next + 1 < ev.size() && ev[next + 1].type == EventType::node) c.near_child = ev[next + 1].node;
  } else if (ev[next].type == EventType::node) {
    bool below = ev[next].node == e.node + 1;  // the child below is the next node (depth-first order)
    bool near_side = below == c.near_is_below;
    c.crossing = near_side ? Crossing::near_only : Crossing::far_only;
    (near_side ? c.near_child : c.far_child) = ev[next].node;
  } else {
    return c;
  }
  c.valid = true;
  return c;
}

}  // namespace

NodeCrossing node_crossing(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  NodeCrossing c;
  const std::vector<Event>& ev = ray.events;
  if (s.node_event < 0 || ev[size_t(s.node_event)].type != EventType::node) return c;
  const Event& e = ev[size_t(s.node_event)];
  const TraceNode* n = find_node(trace, e.node);
  size_t next = size_t(s.node_event) + 1;
  if (!n || n->leaf || n->axis < 0 || next >= ev.size()) return c;  // no split plane (octree): no crossing
  c.node_event = s.node_event;
  c.node = e.node;
  if (n->has_plane) return bsp_crossing(*n, ray, s, c);
  c.axis = n->axis;
  c.split = n->split;
  c.t_min = e.t_min_node;
  c.t_max = e.t_max_node;
  // t* as the kernel computes it, by the direction's reciprocal. The near child is the side the ray starts in
  // (the slides' definition); an origin on the plane starts in the side its direction points into. (The
  // kernel orders the children by the direction's sign bit: the same child whenever the ray crosses the
  // plane at t* >= 0, and when it does not, only one child is visited either way.)
  float o = ray.ray.origin[c.axis], d = ray.ray.direction[c.axis];
  c.t_star = (c.split - o) * (1.f / d);
  c.near_is_below = o < c.split ? true : o > c.split ? false : !std::signbit(d);
  // Which children the walk visits from here, by the events that follow (the child below the plane is the
  // node right after its parent in depth-first order).
  if (ev[next].type == EventType::push) {
    c.crossing = std::isnan(c.t_star) ? Crossing::in_plane : Crossing::both;
    c.near_is_below = !std::signbit(d);  // both visited: the near one is the first (see above)
    c.far_child = ev[next].node;
    if (next + 1 < ev.size() && ev[next + 1].type == EventType::node) c.near_child = ev[next + 1].node;
  } else if (ev[next].type == EventType::node) {
    bool below = ev[next].node == e.node + 1;
    bool near_side = below == c.near_is_below;
    c.crossing = near_side ? Crossing::near_only : Crossing::far_only;
    (near_side ? c.near_child : c.far_child) = ev[next].node;
  } else {
    return c;
  }
  c.valid = true;
  return c;
}

}  // namespace raystep::replay
