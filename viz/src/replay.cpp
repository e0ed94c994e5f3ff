#include "replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "raystep/accel/bsp.h"
#include "raystep/geometry/exact.h"
#include "raystep/geometry/triangle.h"
#include "raystep/geometry/triangle_moller.h"
#include "raystep/lesson/tree_nodes.h"

namespace raystep::viz {

const char* primStateName(PrimState s) {
  switch (s) {
    case PrimState::pending:
      return "pending";
    case PrimState::testing:
      return "testing";
    case PrimState::hit:
      return "hit";
    case PrimState::missed:
      return "missed";
    case PrimState::skipped:
      return "skipped (mailbox)";
  }
  return "";
}

const char* crossingName(Crossing c) {
  switch (c) {
    case Crossing::nearOnly:
      return "near child only";
    case Crossing::farOnly:
      return "far child only";
    case Crossing::both:
      return "both children";
    case Crossing::inPlane:
      return "both children (the ray lies in the plane)";
  }
  return "";
}

const char* axisName(int axis) {
  static const char* names[] = {"x", "y", "z"};
  return axis >= 0 && axis < 3 ? names[axis] : "none";
}

namespace {

bool isTreeEvent(EventType t) {
  return t == EventType::node || t == EventType::push || t == EventType::pop || t == EventType::leaf ||
         t == EventType::box_test || t == EventType::skip;
}

std::string num(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", double(v));
  return buf;
}

}  // namespace

ReplayState replayAt(const TracedRay& ray, int step) {
  ReplayState s;
  const std::vector<Event>& ev = ray.events;
  if (ev.empty()) return s;
  step = std::clamp(step, 0, int(ev.size()) - 1);
  s.step = step;
  s.event = &ev[size_t(step)];

  // Walk the log up to the current event, as the kernel did.
  std::unordered_map<int32_t, size_t> tested;  // prim -> its mailbox entry
  std::unordered_set<int32_t> left;            // nodes in visitedNodes
  std::unordered_set<int32_t> skipped;         // BVH: popped and skipped, never visited
  for (int i = 0; i <= step; ++i) {
    const Event& e = ev[size_t(i)];
    switch (e.type) {
      case EventType::cell:
        if (s.cellEvent >= 0) s.visitedCellEvents.push_back(s.cellEvent);
        s.cellEvent = i;
        s.hasInterval = true;
        s.tMin = e.t_enter;
        s.tMax = e.t_exit;
        ++s.counters.cells;
        break;
      case EventType::node:
      case EventType::pop:
      case EventType::leaf:
        // The walk moves to another node (a leaf event names the node it is already at).
        if (e.type != EventType::leaf && s.nodeEvent >= 0) {
          int32_t from = ev[size_t(s.nodeEvent)].node;
          if (!skipped.count(from) && left.insert(from).second) s.visitedNodes.push_back(from);
        }
        s.nodeEvent = i;
        s.hasInterval = true;
        s.tMin = e.t_min_node;
        s.tMax = e.t_max_node;
        if (e.type == EventType::node) ++s.counters.nodes;
        if (e.type == EventType::pop) {
          ++s.counters.pops;
          if (!s.stack.empty()) s.stack.pop_back();
        }
        break;
      case EventType::box_test:  // BVH: a child's box tested; the inner node stays the current one
        ++s.counters.box_tests;
        break;
      case EventType::skip:  // BVH: the popped entry (the current node) is not visited
        if (skipped.insert(e.node).second) s.skippedNodes.push_back(e.node);
        break;
      case EventType::push:  // the far child waits on the stack; the inner node stays the current one
        ++s.counters.pushes;
        s.stack.push_back(StackEntry{e.node, e.depth, e.t_min_node, e.t_max_node, i});
        break;
      case EventType::prim_test: {
        ++s.counters.prim_tests;
        MailboxEntry m;
        m.prim = e.prim;
        m.testedInCellEvent = s.cellEvent;
        if (s.cellEvent >= 0)
          std::copy(ev[size_t(s.cellEvent)].cell, ev[size_t(s.cellEvent)].cell + 3, m.cell);
        if (s.nodeEvent >= 0) m.leaf = ev[size_t(s.nodeEvent)].node;
        m.hit = e.hit;
        m.t = e.t;
        tested.emplace(e.prim, s.mailbox.size());
        s.mailbox.push_back(m);
        if (e.hit) {
          ++s.counters.prim_hits;
          // A tie (the same t) goes to the lower primitive id, as in the kernels.
          bool lostTie = s.nearestPrim >= 0 && e.t == s.nearestT && e.prim > s.nearestPrim;
          if (!lostTie) {
            s.nearestPrim = e.prim;
            s.nearestT = e.t;
            s.deferred = false;
          }
        }
        break;
      }
      case EventType::mailbox_hit:
        ++s.counters.mailbox_hits;
        if (auto it = tested.find(e.prim); it != tested.end()) ++s.mailbox[it->second].skips;
        break;
      case EventType::hit_deferred:
        s.deferred = true;
        break;
      case EventType::hit_accepted:
        s.accepted = true;
        s.deferred = false;
        s.reason = e.reason;
        s.nearestPrim = e.prim;
        s.nearestT = e.t;
        break;
      case EventType::ray_end:
        s.ended = true;
        break;
      default:
        break;
    }
  }

  // The primitives of the current cell (or leaf): the tests and mailbox hits between it and the next one.
  int blockStart = std::max(s.cellEvent, s.nodeEvent);
  s.blockEvent = blockStart;
  if (blockStart >= 0) {
    for (size_t i = size_t(blockStart) + 1; i < ev.size(); ++i) {
      const Event& e = ev[i];
      if (e.type == EventType::cell || isTreeEvent(e.type) || e.type == EventType::ray_end) break;
      if (e.type != EventType::prim_test && e.type != EventType::mailbox_hit) continue;
      PrimMark p;
      p.prim = e.prim;
      if (int(i) > step)
        p.state = PrimState::pending;
      else if (e.type == EventType::mailbox_hit)
        p.state = PrimState::skipped;
      else if (int(i) == step)
        p.state = PrimState::testing;
      else
        p.state = e.hit ? PrimState::hit : PrimState::missed;
      p.t = e.t;
      p.hit = e.type == EventType::prim_test && e.hit;
      s.prims.push_back(p);
    }
  }
  return s;
}

int findEvent(const TracedRay& ray, int from, EventType type, bool forward) {
  int n = int(ray.events.size());
  if (forward) {
    for (int i = std::max(from + 1, 0); i < n; ++i)
      if (ray.events[size_t(i)].type == type) return i;
  } else {
    for (int i = std::min(from - 1, n - 1); i >= 0; --i)
      if (ray.events[size_t(i)].type == type) return i;
  }
  return -1;
}

int nthEvent(const TracedRay& ray, EventType type, int k) {
  int seen = 0;
  for (size_t i = 0; i < ray.events.size(); ++i)
    if (ray.events[i].type == type && ++seen == k) return int(i);
  return -1;
}

bool isTreeRay(const TracedRay& ray) {
  for (const Event& e : ray.events)
    if (isTreeEvent(e.type)) return true;
  return false;
}

const TraceNode* findNode(const Trace& trace, int32_t id) {
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
NodeCrossing bspCrossing(const TraceNode& n, const TracedRay& ray, const ReplayState& s, NodeCrossing c) {
  const std::vector<Event>& ev = ray.events;
  const Event& e = ev[size_t(s.nodeEvent)];
  size_t next = size_t(s.nodeEvent) + 1;
  c.general = true;
  c.normal = n.normal;
  c.offset = n.offset;
  c.tMin = e.t_min_node;
  c.tMax = e.t_max_node;
  const glm::vec3 o = ray.ray.origin, d = ray.ray.direction;
  c.originSide = double(n.normal.x) * o.x + double(n.normal.y) * o.y + double(n.normal.z) * o.z - n.offset;
  c.nDotDir = double(n.normal.x) * d.x + double(n.normal.y) * d.y + double(n.normal.z) * d.z;
  const BspCrossing k =
      bsp_crossing(BspPlane{n.normal, n.offset}, o, d, std::max(std::fabs(c.tMin), std::fabs(c.tMax)));
  // The near child is the side the ray starts in (the slides'); on the plane, the side the ray moves into.
  c.nearIsBelow = c.originSide < 0 ? true : c.originSide > 0 ? false : k.below_first;
  c.tLo = k.t_lo;
  c.tHi = k.t_hi;
  if (k.kind == BspCrossing::crosses)
    c.tStar = float(-c.originSide / c.nDotDir);
  else if (k.kind == BspCrossing::stays)
    c.tStar = k.below_first == (c.nDotDir >= 0.0) ? kInfinity : -kInfinity;  // never reached, or behind
  else
    c.tStar = std::numeric_limits<float>::quiet_NaN();
  if (next >= ev.size()) return c;
  if (ev[next].type == EventType::push) {
    c.crossing = k.kind == BspCrossing::undecided ? Crossing::inPlane : Crossing::both;
    c.nearIsBelow = k.below_first;  // both visited: the near one is the first (the origin's side, or on the
                                    // plane within rounding the side the ray moves into)
    c.farChild = ev[next].node;
    if (next + 1 < ev.size() && ev[next + 1].type == EventType::node) c.nearChild = ev[next + 1].node;
  } else if (ev[next].type == EventType::node) {
    bool below = ev[next].node == e.node + 1;  // the child below is the next node (depth-first order)
    bool nearSide = below == c.nearIsBelow;
    c.crossing = nearSide ? Crossing::nearOnly : Crossing::farOnly;
    (nearSide ? c.nearChild : c.farChild) = ev[next].node;
  } else {
    return c;
  }
  c.valid = true;
  return c;
}

}  // namespace

NodeCrossing nodeCrossing(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  NodeCrossing c;
  const std::vector<Event>& ev = ray.events;
  if (s.nodeEvent < 0 || ev[size_t(s.nodeEvent)].type != EventType::node) return c;
  const Event& e = ev[size_t(s.nodeEvent)];
  const TraceNode* n = findNode(trace, e.node);
  size_t next = size_t(s.nodeEvent) + 1;
  if (!n || n->leaf || n->axis < 0 || next >= ev.size()) return c;  // no split plane (octree): no crossing
  c.nodeEvent = s.nodeEvent;
  c.node = e.node;
  if (n->has_plane) return bspCrossing(*n, ray, s, c);
  c.axis = n->axis;
  c.split = n->split;
  c.tMin = e.t_min_node;
  c.tMax = e.t_max_node;
  // t* as the kernel computes it, by the direction's reciprocal. The near child is the side the ray starts in
  // (the slides' definition); an origin on the plane starts in the side its direction points into. (The
  // kernel orders the children by the direction's sign bit: the same child whenever the ray crosses the
  // plane at t* >= 0, and when it does not, only one child is visited either way.)
  float o = ray.ray.origin[c.axis], d = ray.ray.direction[c.axis];
  c.tStar = (c.split - o) * (1.f / d);
  c.nearIsBelow = o < c.split ? true : o > c.split ? false : !std::signbit(d);
  // Which children the walk visits from here, by the events that follow (the child below the plane is the
  // node right after its parent in depth-first order).
  if (ev[next].type == EventType::push) {
    c.crossing = std::isnan(c.tStar) ? Crossing::inPlane : Crossing::both;
    c.nearIsBelow = !std::signbit(d);  // both visited: the near one is the first (see above)
    c.farChild = ev[next].node;
    if (next + 1 < ev.size() && ev[next + 1].type == EventType::node) c.nearChild = ev[next + 1].node;
  } else if (ev[next].type == EventType::node) {
    bool below = ev[next].node == e.node + 1;
    bool nearSide = below == c.nearIsBelow;
    c.crossing = nearSide ? Crossing::nearOnly : Crossing::farOnly;
    (nearSide ? c.nearChild : c.farChild) = ev[next].node;
  } else {
    return c;
  }
  c.valid = true;
  return c;
}

bool isOctreeRay(const Trace* trace, const TracedRay& ray) {
  if (trace) return trace->structure.kind == "octree";
  // Without a trace: the octree pushes the cell it is at (its frame), a kd-tree the far child.
  int32_t at = -1;
  for (const Event& e : ray.events) {
    if (e.type == EventType::node) at = e.node;
    if (e.type == EventType::push) return e.node == at;
  }
  return false;
}

std::string octantName(int octant) {
  std::string s;
  for (int a = 0; a < 3; ++a) s += std::string(a ? " " : "") + axisName(a) + ((octant >> a) & 1 ? "+" : "-");
  return s;
}

OctreeChoice octreeChoice(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  OctreeChoice c;
  const std::vector<Event>& ev = ray.events;
  if (s.nodeEvent < 0 || ev[size_t(s.nodeEvent)].type != EventType::node) return c;
  const Event& e = ev[size_t(s.nodeEvent)];
  const TraceNode* n = findNode(trace, e.node);
  if (!n || n->leaf || n->children.size() != 8) return c;
  c.nodeEvent = s.nodeEvent;
  c.node = e.node;
  c.depth = e.depth;
  c.tEnter = e.t_min_node;
  c.tExit = e.t_max_node;
  // The planes' t as the kernel computes them (octree.h): float, by the direction's reciprocal; the cell's
  // centre as the build's 0.5 (lo + hi). In the frame where every direction component is positive (the
  // paper's reflection), t0 is the entry face's t, t1 the exit face's.
  const glm::vec3 o = ray.ray.origin, d = ray.ray.direction;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.f / d[a];
    const bool neg = std::signbit(d[a]);
    const float mid = 0.5f * (n->box.lo[a] + n->box.hi[a]);
    c.moving[a] = std::isfinite(inv);
    if (c.moving[a]) {
      c.t0[a] = ((neg ? n->box.hi[a] : n->box.lo[a]) - o[a]) * inv;
      c.t1[a] = ((neg ? n->box.lo[a] : n->box.hi[a]) - o[a]) * inv;
      c.tMid[a] = (mid - o[a]) * inv;
    } else {
      c.t0[a] = -kInfinity;
      c.t1[a] = kInfinity;
      c.tMid[a] = (o[a] >= mid) != neg ? -kInfinity : kInfinity;
    }
  }
  const float tIn = std::max({c.t0[0], c.t0[1], c.t0[2]});
  c.entryAxis = c.t0[0] >= c.t0[1] && c.t0[0] >= c.t0[2] ? 0 : (c.t0[1] >= c.t0[2] ? 1 : 2);
  int mask = 0;
  for (int a = 0; a < 3; ++a) mask |= int(std::signbit(d[a])) << a;
  // Revelles' walk in the reflected frame (reflected child r is real child r ^ mask).
  static const int kNext[8][3] = {{1, 2, 4}, {8, 3, 5}, {3, 8, 6}, {8, 8, 7},
                                  {5, 6, 8}, {8, 7, 8}, {7, 8, 8}, {8, 8, 8}};
  int r = 0;
  for (int b = 0; b < 3; ++b)
    if (b != c.entryAxis && c.tMid[b] < tIn) r |= 1 << b;
  while (r < 8 && c.path.size() < 8) {
    OctreeChildStep st;
    st.octant = r ^ mask;
    st.node = n->children[size_t(st.octant)];
    float ct1[3];
    for (int a = 0; a < 3; ++a) ct1[a] = (r >> a) & 1 ? c.t1[a] : c.tMid[a];
    st.exitAxis = ct1[0] <= ct1[1] && ct1[0] <= ct1[2] ? 0 : (ct1[1] <= ct1[2] ? 1 : 2);
    st.tExit = ct1[st.exitAxis];
    r = kNext[r][st.exitAxis];
    st.leavesParent = r == 8;
    c.path.push_back(st);
  }
  // The children the walk visits: the node events one level down between this cell's push and its pop.
  int depth = e.depth;
  for (size_t i = size_t(s.nodeEvent) + 1; i < ev.size(); ++i) {
    const Event& x = ev[i];
    if (x.type == EventType::pop && x.node == e.node) break;
    if (x.type == EventType::hit_accepted || x.type == EventType::ray_end) break;
    if (x.type != EventType::node || x.depth != depth + 1) continue;
    c.visited.push_back(x.node);
    auto it = std::find(n->children.begin(), n->children.end(), x.node);
    c.visitedOctants.push_back(it == n->children.end() ? -1 : int(it - n->children.begin()));
    if (int(i) <= s.step) ++c.visitedSoFar;
  }
  c.valid = true;
  return c;
}

bool isBvhKind(const std::string& kind) {
  return kind.rfind("bvh", 0) == 0;
}

bool isBvhRay(const Trace* trace, const TracedRay& ray) {
  if (trace && isBvhKind(trace->structure.kind)) return true;
  for (const Event& e : ray.events)
    if (e.type == EventType::box_test || e.type == EventType::skip) return true;
  return false;
}

BvhChoice bvhChoice(const TracedRay& ray, const ReplayState& s) {
  BvhChoice c;
  const std::vector<Event>& ev = ray.events;
  if (s.nodeEvent < 0 || ev[size_t(s.nodeEvent)].type != EventType::node) return c;
  c.nodeEvent = s.nodeEvent;
  c.node = ev[size_t(s.nodeEvent)].node;
  // The node's box tests and pushes follow it; the next node event is the child entered first.
  size_t i = size_t(s.nodeEvent) + 1;
  int lastTest = -1;
  for (; i < ev.size(); ++i) {
    const Event& e = ev[i];
    if (e.type == EventType::box_test) {
      BoxTestMark m;
      m.child = e.node;
      m.hit = e.hit;
      m.tNear = e.t_min_node;
      m.tFar = e.t_max_node;
      m.event = int(i);
      m.done = int(i) <= s.step;
      c.tests.push_back(m);
      lastTest = int(i);
    } else if (e.type == EventType::push) {
      c.pushed.push_back(e.node);
    } else {
      break;
    }
  }
  if (c.tests.empty()) return c;
  if (i < ev.size() && ev[i].type == EventType::node) c.first = ev[i].node;
  c.decided = s.step >= lastTest;
  c.valid = true;
  return c;
}

std::string describeEvent(const Event& e) {
  std::string s = std::to_string(e.seq) + "  " + event_type_name(e.type);
  switch (e.type) {
    case EventType::cell:
      s += "  (" + std::to_string(e.cell[0]) + "," + std::to_string(e.cell[1]) + "," +
           std::to_string(e.cell[2]) + ")  t " + num(e.t_enter) + ".." + num(e.t_exit) + "  next " +
           axisName(e.next_axis);
      break;
    case EventType::node:
    case EventType::push:
    case EventType::pop:
    case EventType::leaf:
      s += (e.type == EventType::node ? "  " : "  node ") + std::to_string(e.node) + " depth " +
           std::to_string(e.depth) + "  t " + num(e.t_min_node) + ".." + num(e.t_max_node);
      break;
    case EventType::box_test:
      s += (e.parent < 0 ? "  root " + std::to_string(e.node)
                         : "  child " + std::to_string(e.node) + " of " + std::to_string(e.parent)) +
           (e.hit ? ": hit [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "]" : ": miss");
      break;
    case EventType::skip:
      s += "  node " + std::to_string(e.node) + " t_near " + num(e.t_min_node) + " (beyond the nearest hit)";
      break;
    case EventType::prim_test:
      s += "  prim " + std::to_string(e.prim) + (e.hit ? ": hit at t " + num(e.t) : ": miss");
      break;
    case EventType::mailbox_hit:
      s += "  prim " + std::to_string(e.prim) + " skipped (tested before)";
      break;
    case EventType::hit_deferred:
      s += "  prim " + std::to_string(e.prim) + " t " + num(e.t) + " > cell exit " + num(e.t_exit);
      break;
    case EventType::hit_accepted:
      s += "  prim " + std::to_string(e.prim) + " t " + num(e.t) + " (" + accept_reason_name(e.reason) + ")";
      break;
    case EventType::ray_end:
      s += e.prim >= 0 ? "  hit prim " + std::to_string(e.prim) + " at t " + num(e.t) : "  miss";
      break;
    default:
      break;
  }
  return s;
}

namespace {

// A barycentric in Möller–Trumbore's rejection: "u = -2.4e-08 < 0"; u + v > 1 by its excess over 1, which
// two digits of u + v itself would hide.
std::string mtReason(const MollerTrumboreValues& m) {
  char buf[96];
  std::string f = m.failed;
  if (f == "u < 0" || f == "u > 1")
    std::snprintf(buf, sizeof buf, "u = %.2g %s", double(m.u), f == "u < 0" ? "< 0" : "> 1");
  else if (f == "v < 0")
    std::snprintf(buf, sizeof buf, "v = %.2g < 0", double(m.v));
  else if (f == "u + v > 1")
    std::snprintf(buf, sizeof buf, "u + v = 1 + %.2g > 1", double((double(m.u) + double(m.v)) - 1.0));
  else if (f == "t")
    std::snprintf(buf, sizeof buf, "t = %.4g outside the ray's interval", double(m.t));
  else
    return "the ray is parallel to the plane, det = 0";
  return buf;
}

}  // namespace

std::string compareTriangleTests(const TracedRay& ray, const TracePrimitive& p) {
  if (p.type != PrimType::triangle) return "";
  // The watertight test again on the same float inputs; the exact counters tell how it decided (the most
  // careful level it needed: an edge within its error bound goes to the double filter, and from there, if the
  // filter cannot decide either, to rational arithmetic).
  ExactCounters before = exact_counters();
  TriangleHit h;
  bool watertight = intersect_triangle(ray.ray, p.v[0], p.v[1], p.v[2], &h);
  ExactCounters after = exact_counters();
  const char* how = after.exact != before.exact         ? "settled by exact rational arithmetic"
                    : after.filtered != before.filtered ? "settled by the double-precision filter"
                                                        : "float alone";
  MollerTrumboreValues m = moller_trumbore_values(ray.ray, p.v[0], p.v[1], p.v[2], ray.ray.tmax);
  return std::string("This ray and triangle alone: watertight ") + (watertight ? "hit" : "miss") + " (" +
         how + "); Möller–Trumbore " + (m.failed ? "miss (" + mtReason(m) + ")" : std::string("hit")) + ".";
}

namespace {

const TracePrimitive* findPrimitive(const Trace* trace, int32_t id) {
  if (!trace) return nullptr;
  auto it = std::lower_bound(trace->primitives.begin(), trace->primitives.end(), id,
                             [](const TracePrimitive& p, int32_t v) { return p.id < v; });
  if (it != trace->primitives.end() && it->id == id) return &*it;
  for (const TracePrimitive& p : trace->primitives)
    if (p.id == id) return &p;
  return nullptr;
}

// A primitive test in a cell or leaf (`where`): a nearer hit, a tie lost to a lower id, or no nearer hit; for
// a triangle, a second line with the watertight test and Möller–Trumbore on this very ray and triangle.
std::string explainPrimTest(const Trace* trace, const TracedRay& ray, const Event& e, const ReplayState& s,
                            const std::string& where) {
  std::string head = "Primitive " + std::to_string(e.prim) + where, text;
  if (e.hit && s.nearestPrim != e.prim)
    text = head + ": hit at t = " + num(e.t) + ", the same t as the nearest hit so far, primitive " +
           std::to_string(s.nearestPrim) + ": a tie goes to the lower id, which stays the nearest.";
  else if (e.hit && s.step > 0 && replayAt(ray, s.step - 1).nearestPrim == e.prim)
    // Without mailboxes a primitive in several cells or leaves is tested again, and hits again at the same t.
    text = head + ": hit at t = " + num(e.t) +
           " again: it is already the nearest hit (tested before, in an "
           "earlier cell or leaf); the nearest hit stays.";
  else if (e.hit)
    text = head + ": hit at t = " + num(e.t) + ", nearer than any hit so far. It becomes the nearest hit.";
  else
    text = head + ": no hit nearer than the nearest so far.";
  if (const TracePrimitive* p = findPrimitive(trace, e.prim)) {
    std::string line = compareTriangleTests(ray, *p);
    if (!line.empty()) text += "\n" + line;
  }
  return text;
}

// The mailbox's mechanism (mailbox.h), for a skip: each ray takes the next number as it is cast, a test writes
// it into the primitive's mailbox, a mailbox that already holds the ray's own number means "tested": skip.
// Here the rays are numbered in the order the pixel cast them.
std::string mailboxStamp(const Trace* trace, const TracedRay& ray, int32_t prim) {
  size_t number = 1;
  if (trace)
    for (size_t i = 0; i < trace->rays.size(); ++i)
      if (&trace->rays[i] == &ray) number = i + 1;
  return "\nPrimitive " + std::to_string(prim) + "'s mailbox holds ray number " + std::to_string(number) +
         ", this ray's own: each ray takes the next number as it is cast and writes it into the mailbox of "
         "every primitive it tests. The next ray's number matches no mailbox: nothing is cleared between rays.";
}

std::string explainGridRule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const Event* cell = s.cellEvent >= 0 ? &ray.events[size_t(s.cellEvent)] : nullptr;
  switch (e.type) {
    case EventType::hit_deferred:
      return "t(hit) = " + num(e.t) + " > t_exit(cell) = " + num(e.t_exit) +
             ": a later cell may hold a nearer hit. Keep it as the nearest so far and go on.";
    case EventType::hit_accepted:
      if (e.reason == AcceptReason::inside_cell && cell)
        return "Traverse until tmin(cell) > tmax(ray):\ntmin(next cell) = t_exit = " + num(cell->t_exit) +
               " > tmax(ray) = t(hit) = " + num(e.t) + "  =>  stop, the hit is final.";
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      return "The walk left the grid; the nearest hit t = " + num(e.t) + " is final.";
    case EventType::ray_end:
      if (e.prim < 0) return "Miss: the walk left the grid without a hit.";
      return "Result: primitive " + std::to_string(e.prim) + " at t = " + num(e.t) + ".";
    case EventType::cell:
      if (e.next_axis < 0)
        return "min t_max = " + num(std::min({e.t_max.x, e.t_max.y, e.t_max.z})) +
               " > t_exit(grid) = " + num(e.t_exit) + ": the walk ends in this cell.";
      // The kernel picks the axis on entering the cell; a hit found in the cell may end the walk before the
      // step.
      if (findEvent(ray, s.step, EventType::cell, true) < 0 &&
          findEvent(ray, s.step, EventType::hit_accepted, true) >= 0)
        return "The 3D-DDA would step along " + std::string(axisName(e.next_axis)) + " next (t_max." +
               axisName(e.next_axis) + " = " + num(e.t_max[e.next_axis]) +
               " is the smallest t_max), but the walk ends in this cell: a hit found here lies before its "
               "exit.";
      return "Step along " + std::string(axisName(e.next_axis)) + ": t_max." + axisName(e.next_axis) + " = " +
             num(e.t_max[e.next_axis]) + " is the smallest t_max.";
    case EventType::ray_begin: {
      int first = findEvent(ray, 0, EventType::cell, true);
      if (first < 0) return "The ray misses the grid's box (slab test): no cell to visit.";
      return "Slab test: the ray enters the grid's box at t = " + num(ray.events[size_t(first)].t_enter) +
             "; the walk starts in the cell that contains that point.";
    }
    case EventType::prim_test: {
      std::string where = cell ? " in cell (" + std::to_string(cell->cell[0]) + "," +
                                     std::to_string(cell->cell[1]) + "," + std::to_string(cell->cell[2]) + ")"
                               : "";
      return explainPrimTest(trace, ray, e, s, where);
    }
    case EventType::mailbox_hit: {
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim)
          return "Primitive " + std::to_string(e.prim) + " was already tested in cell (" +
                 std::to_string(m.cell[0]) + "," + std::to_string(m.cell[1]) + "," +
                 std::to_string(m.cell[2]) +
                 ") for this ray (it spans several cells): the mailbox skips the test." +
                 mailboxStamp(trace, ray, e.prim);
      return "Primitive " + std::to_string(e.prim) + " was already tested for this ray: skipped." +
             mailboxStamp(trace, ray, e.prim);
    }
    default:
      return "";
  }
}

std::string side(bool below) {
  return below ? "below the plane" : "above the plane";
}

// "node 2 (LL)": the id the trace uses and the path in the slides' notation (none for a wide BVH's node).
std::string nodeName(const Trace* trace, int32_t id) {
  if (id < 0) return "the child";
  const std::string path = trace ? trace_node_path_text(*trace, id) : "";
  return "node " + std::to_string(id) + (path.empty() ? "" : " (" + path + ")");
}

std::string vec(const glm::vec3& v) {
  return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")";
}

// A general BSP node's plane and decision, in the lecture's words: the same walk as the kd-tree's with
// t* = (d - n.o) / (n.dir) instead of (split - o.a) / d.a.
std::string explainBspNode(const Trace* trace, const NodeCrossing& c) {
  std::string head =
      "Inner " + nodeName(trace, c.node) + ", plane n.p = d with n = " + vec(c.normal) +
      ", d = " + num(c.offset) + ".\nThe origin's signed distance n.o - d = " + num(float(c.originSide)) +
      " (" + (c.originSide < 0 ? "below" : "above") + " the plane); n.dir = " + num(float(c.nDotDir)) + ".\n";
  std::string nearName = nodeName(trace, c.nearChild) + " (" + side(c.nearIsBelow) + ")";
  std::string farName = nodeName(trace, c.farChild) + " (" + side(!c.nearIsBelow) + ")";
  if (c.crossing == Crossing::inPlane)
    return head +
           "n.dir is 0 within rounding and the ray lies on the plane, or too near it to tell: t* is "
           "undefined, "
           "the ray may touch both children over the whole interval.\nVisit the near child, " +
           nearName + "; push the far child, " + farName + ", with all of [" + num(c.tMin) + ", " +
           num(c.tMax) + "].";
  if (!std::isfinite(c.tStar)) {
    std::string only = c.crossing == Crossing::nearOnly ? nearName : farName;
    return head +
           "n.dir is 0 within rounding: the ray runs parallel to the plane and stays on its origin's "
           "side over [t_min, t_max].\nOnly " +
           only + " is visited: Intersect(" + (c.crossing == Crossing::nearOnly ? "near" : "far") +
           ", t_min, t_max).";
  }
  head += "t* = (d - n.o) / (n.dir) = " + num(c.tStar) +
          ". The near child is the side the ray starts in: " + side(c.nearIsBelow) +
          (c.nDotDir > 0 ? " (n.dir > 0: the ray moves up the normal)"
                         : " (n.dir < 0: the ray moves down the normal)") +
          ".\n";
  switch (c.crossing) {
    case Crossing::nearOnly:
      if (c.tStar < 0)
        return head + "t* = " + num(c.tStar) +
               " < 0: the plane lies behind the origin and the ray moves away from it, staying on its own "
               "side.\nOnly the near child, " +
               nearName + ", is visited: Intersect(near, t_min, t_max).";
      return head + "t* = " + num(c.tStar) + " > t_max = " + num(c.tMax) +
             ": the ray leaves the node's cell before it reaches the plane.\nOnly the near child, " +
             nearName + ", is visited: Intersect(near, t_min, t_max).";
    case Crossing::farOnly:
      return head + "0 <= t* = " + num(c.tStar) + " < t_min = " + num(c.tMin) +
             ": the ray crossed the plane before it entered the node's cell.\nOnly the far child, " + farName +
             ", is visited: Intersect(far, t_min, t_max).";
    case Crossing::both: {
      bool inside = c.tStar >= c.tMin && c.tStar <= c.tMax;
      return head +
             (inside ? "t_min = " + num(c.tMin) + " <= t* <= t_max = " + num(c.tMax)
                     : "t* is at the edge of [" + num(c.tMin) + ", " + num(c.tMax) +
                           "] (within the walk's rounding margin)") +
             ": the ray crosses both children.\nIntersect(near = " + nearName + ", t_min, t*) now; push " +
             "Intersect(far = " + farName + ", t*, t_max) for later (t* widened to [" + num(c.tLo) + ", " +
             num(c.tHi) + "], its rounding bound, so no hit on the plane is lost).";
    }
    default:
      return head;
  }
}

// The octree's walk (Revelles et al.): the current inner cell's child order by its planes.
std::string octreeOrderText(const OctreeChoice& c) {
  std::string t;
  if (c.entryAxis >= 0 && c.moving[c.entryAxis]) {
    t = "Entry plane: the ray enters the cell through its face normal to " +
        std::string(axisName(c.entryAxis)) + " (t0." + axisName(c.entryAxis) + " = " +
        num(c.t0[c.entryAxis]) + ", the largest entry t)";
  } else {
    t = "The ray starts inside the cell";
  }
  std::vector<std::string> crossed;
  for (int b = 0; b < 3; ++b)
    if (b != c.entryAxis && c.moving[b])
      crossed.push_back(
          std::string(axisName(b)) + " centre plane at t = " + num(c.tMid[b]) +
          (c.tMid[b] < c.t0[c.entryAxis] ? " (before: the far half)" : " (after: the near half)"));
  if (!crossed.empty()) {
    t += "; ";
    for (size_t k = 0; k < crossed.size(); ++k) t += (k ? ", " : "") + crossed[k];
  }
  if (c.path.empty()) return t + ".";
  t += ".\nFirst child: " + std::to_string(c.path[0].node) + " [" + octantName(c.path[0].octant) + "].";
  t += " Next by the exit plane (the smallest exit t):";
  for (size_t k = 0; k < c.path.size(); ++k) {
    const OctreeChildStep& st = c.path[k];
    t += std::string(k ? ";" : "") + " " + std::to_string(st.node) + " leaves by " + axisName(st.exitAxis) +
         (st.leavesParent ? " (the cell's face) at t = " + num(st.tExit) + ": done"
                          : " at t = " + num(st.tExit) + " -> " + std::to_string(c.path[k + 1].node));
  }
  t += ".";
  // The events are the truth: a grazed child (within the rounding margin) is walked too, and the walk stops
  // early once a child starts beyond the nearest hit.
  std::vector<int32_t> planned;
  for (const OctreeChildStep& st : c.path) planned.push_back(st.node);
  if (!c.visited.empty() && c.visited != planned) {
    t += "\nThe walk visits ";
    for (size_t k = 0; k < c.visited.size(); ++k) t += (k ? ", " : "") + std::to_string(c.visited[k]);
    std::vector<std::string> why;
    if (c.visited[0] != planned[0] && c.path[0].tExit < c.tEnter)
      why.push_back("the ray starts inside the cell: the children before its start are passed over");
    if (c.visited.back() != planned.back())
      why.push_back("it stops where a child starts beyond the ray's end or the nearest hit");
    for (int32_t v : c.visited)
      if (std::find(planned.begin(), planned.end(), v) == planned.end()) {
        why.push_back("a child the ray grazes within the rounding margin is walked too");
        break;
      }
    t += " (";
    for (size_t k = 0; k < why.size(); ++k) t += (k ? "; " : "") + why[k];
    t += ").";
  }
  return t;
}

std::string explainOctreeRule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const std::vector<Event>& ev = ray.events;
  size_t next = size_t(s.step) + 1;
  const Event* after = next < ev.size() ? &ev[next] : nullptr;
  std::string cell = "Cell " + std::to_string(e.node) + " (depth " + std::to_string(e.depth) +
                     ", [t_enter, t_exit] = [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "])";
  switch (e.type) {
    case EventType::ray_begin: {
      int first = findEvent(ray, 0, EventType::node, true);
      if (first < 0) return "The ray misses the octree's root cube (slab test): no cell to visit.";
      const Event& root = ev[size_t(first)];
      return "Slab test: the ray meets the root cube over [t_enter, t_exit] = [" + num(root.t_min_node) +
             ", " + num(root.t_max_node) +
             "]. The walk is parametric and top-down (Revelles et al.): from each cell to its children in "
             "the "
             "order the ray crosses them.";
    }
    case EventType::node: {
      if (after && after->type == EventType::leaf) return cell + " is a leaf.";
      std::string text = cell + ": an inner cell, split at its centre into eight octants.";
      if (OctreeChoice c = trace ? octreeChoice(*trace, ray, s) : OctreeChoice{}; c.valid)
        text += "\n" + octreeOrderText(c);
      return text;
    }
    case EventType::push: {
      std::string text =
          "Walk the children of cell " + std::to_string(e.node) +
          " in the order the ray crosses them (each child's [t_enter, t_exit] starts where the "
          "previous one's ends); its frame goes on the stack.";
      if (OctreeChoice c = trace ? octreeChoice(*trace, ray, s) : OctreeChoice{}; c.valid && !c.path.empty())
        text +=
            " First child: " + std::to_string(c.path[0].node) + " [" + octantName(c.path[0].octant) + "].";
      return text;
    }
    case EventType::pop:
      return "Cell " + std::to_string(e.node) + "'s children are done" +
             (s.nearestPrim >= 0
                  ? " (or the next one starts beyond the nearest hit, t = " + num(s.nearestT) + ")"
                  : std::string()) +
             ": back to its parent's next child.";
    case EventType::leaf: {
      size_t k = s.prims.size();
      std::string head = "Leaf cell " + std::to_string(e.node) + " over [t_enter, t_exit] = [" +
                         num(e.t_min_node) + ", " + num(e.t_max_node) + "]";
      if (k == 0) return head + " is empty: nothing to test. Go on with the next child.";
      return head + ": test its " + std::to_string(k) + (k == 1 ? " primitive" : " primitives") +
             " (a primitive lies in every cell it overlaps: the mailbox skips one tested before).";
    }
    case EventType::prim_test: {
      std::string where = s.nodeEvent >= 0 ? " in cell " + std::to_string(ev[size_t(s.nodeEvent)].node) : "";
      return explainPrimTest(trace, ray, e, s, where);
    }
    case EventType::mailbox_hit:
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim && m.leaf >= 0)
          return "Mailbox hit: primitive " + std::to_string(e.prim) + " was already tested in cell " +
                 std::to_string(m.leaf) + " for this ray (it overlaps several cells): skip the test." +
                 mailboxStamp(trace, ray, e.prim);
      return "Mailbox hit: primitive " + std::to_string(e.prim) + " was already tested for this ray: skipped." +
             mailboxStamp(trace, ray, e.prim);
    case EventType::hit_deferred:
      return "The hit t = " + num(e.t) + " lies beyond this cell's exit, t_exit = " + num(e.t_exit) +
             ": a later cell may hold a nearer hit. Keep it and go on: traverse until tmin(cell) > "
             "tmax(ray).";
    case EventType::hit_accepted: {
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      if (e.reason == AcceptReason::inside_cell)
        return "Traverse until tmin(cell) > tmax(ray): the hit t = " + num(e.t) +
               " lies inside this cell (before its t_exit = " + num(s.tMax) +
               "), and every later cell starts at or beyond that exit  =>  stop, the hit is final.";
      if (e.reason == AcceptReason::next_node_beyond)
        return "Traverse until tmin(cell) > tmax(ray): the next child starts beyond the hit t = " + num(e.t) +
               ", and so does every later cell  =>  stop, the hit is final.";
      return "Every cell the ray crosses has been walked. The nearest hit, t = " + num(e.t) + ", is final.";
    }
    case EventType::ray_end:
      if (e.prim < 0) return "Miss: the walk visited every cell the ray crosses without a hit.";
      return "Result: primitive " + std::to_string(e.prim) + " at t = " + num(e.t) + ".";
    default:
      return "";
  }
}

// The kd-tree's stack walk in the lecture's words.
std::string explainTreeRule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const std::vector<Event>& ev = ray.events;
  size_t next = size_t(s.step) + 1;
  const Event* after = next < ev.size() ? &ev[next] : nullptr;
  switch (e.type) {
    case EventType::ray_begin: {
      int first = findEvent(ray, 0, EventType::node, true);
      if (first < 0) return "The ray misses the tree's box (slab test): no node to visit.";
      const Event& root = ev[size_t(first)];
      return "Slab test: the ray meets the root's box over [t_min, t_max] = [" + num(root.t_min_node) + ", " +
             num(root.t_max_node) + "]; the walk starts at the root with that interval.";
    }
    case EventType::node: {
      if (after && after->type == EventType::leaf)
        return "Node " + std::to_string(e.node) + " (depth " + std::to_string(e.depth) + ") is a leaf.";
      NodeCrossing c = trace ? nodeCrossing(*trace, ray, s) : NodeCrossing{};
      if (!c.valid) return "Inner " + nodeName(trace, e.node) + ": the walk goes on in its children.";
      std::string a = axisName(c.axis);
      std::string head = "Inner " + nodeName(trace, c.node) + " splits " + a + " at " + num(c.split) +
                         ". t* = (split - o." + a + ") / d." + a + " = " + num(c.tStar) + ".\n";
      if (c.general) return explainBspNode(trace, c);
      std::string nearName = nodeName(trace, c.nearChild) + " (" + side(c.nearIsBelow) + ")";
      std::string farName = nodeName(trace, c.farChild) + " (" + side(!c.nearIsBelow) + ")";
      switch (c.crossing) {
        case Crossing::nearOnly:
          if (std::isinf(c.tStar))
            return head + "The ray runs parallel to the plane (d." + a +
                   " = 0): it stays on one side.\nOnly " + nearName +
                   " is visited: Intersect(near, t_min, t_max).";
          if (c.tStar < 0)
            return head + "t* = " + num(c.tStar) + " < 0: the plane lies behind the origin (near side: " +
                   side(c.nearIsBelow) +
                   ", the side the ray starts in) and the ray moves away from it.\nOnly the near child, " +
                   nearName + ", is visited: Intersect(near, t_min, t_max).";
          return head + "t* = " + num(c.tStar) + " > t_max = " + num(c.tMax) +
                 ": the ray leaves the node before it reaches the plane.\nOnly the near child, " + nearName +
                 ", is visited: Intersect(near, t_min, t_max).";
        case Crossing::farOnly:
          if (std::isinf(c.tStar))
            return head + "The ray runs parallel to the plane (d." + a +
                   " = 0): it stays on one side.\nOnly " + farName +
                   " is visited: Intersect(far, t_min, t_max).";
          return head + "0 <= t* = " + num(c.tStar) + " < t_min = " + num(c.tMin) +
                 ": the ray crossed the plane before it entered the node.\nOnly the far child, " +
                 farName + ", is visited: Intersect(far, t_min, t_max).";
        case Crossing::both: {
          bool inside = c.tStar >= c.tMin && c.tStar <= c.tMax;
          return head +
                 (inside ? "t_min = " + num(c.tMin) + " <= t* <= t_max = " + num(c.tMax)
                         : "t* is at the edge of [" + num(c.tMin) + ", " + num(c.tMax) +
                               "] (within the walk's rounding margin)") +
                 ": the ray crosses both children.\nIntersect(near = " + nearName +
                 ", t_min, t*) now; push (far = " + farName + ", t*, t_max) for later.";
        }
        case Crossing::inPlane:
          return head +
                 "The ray lies in the split plane (t* = 0 * inf is undefined): it touches both children "
                 "over the whole interval.\nVisit the near child, " +
                 nearName + "; push the far child, " + farName + ", with all of [" + num(c.tMin) + ", " +
                 num(c.tMax) + "].";
      }
      return head;
    }
    case EventType::push: {
      NodeCrossing c =
          trace ? nodeCrossing(*trace, ray, s) : NodeCrossing{};  // of the inner node being split
      bool inPlane = c.valid && c.crossing == Crossing::inPlane;
      return "Push the far child, " + nodeName(trace, e.node) +
             (inPlane ? ", with the whole interval [t_min, t_max] = ["
                      : ", with its part of the ray [t*, t_max] = [") +
             num(e.t_min_node) + ", " + num(e.t_max_node) +
             "]. The walk goes on in the near child; the stack holds " + std::to_string(s.stack.size()) +
             (s.stack.size() == 1 ? " node." : " nodes.");
    }
    case EventType::leaf: {
      size_t k = s.prims.size();
      std::string head =
          "Leaf " + std::to_string(e.node) + " over [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "]";
      if (k == 0) return head + " is empty: nothing to test. Go on with the next node on the stack.";
      return head + ": test its " + std::to_string(k) + (k == 1 ? " primitive" : " primitives") +
             " against the ray (the mailbox skips any tested before).";
    }
    case EventType::pop: {
      std::string head = "Pop " + nodeName(trace, e.node) + " with [t_min, t_max] = [" +
                         num(e.t_min_node) + ", " + num(e.t_max_node) + "]. ";
      bool visited = after && after->type == EventType::node && after->node == e.node;
      if (visited) {
        if (s.nearestPrim < 0) return head + "No hit yet: visit it.";
        if (s.nearestT < e.t_min_node)
          return head + "The nearest hit so far, t = " + num(s.nearestT) +
                 ", lies before its t_min, but by less "
                 "than the walk's safety margin (2^-12 of the larger of |t_min| and |t_max| in the root): "
                 "visit it, "
                 "so that no hit is lost to rounding.";
        return head + "The nearest hit so far, t = " + num(s.nearestT) +
               ", is not before its t_min: a nearer hit may "
               "lie in it, so visit it.";
      }
      const bool bsp = trace && trace->structure.kind == "bsp";
      if (bsp)  // t* is an interval there: the stack is not ordered by t_min
        return head + "The nearest hit t = " + num(s.nearestT) + " < t_min = " + num(e.t_min_node) +
               ": the node starts beyond the hit, so none of its primitives can be nearer. Skip it. A BSP "
               "tree's stack is not ordered by t_min (t* is known within its rounding interval), so every "
               "entry left is popped and judged on its own.";
      return head + "The nearest hit t = " + num(s.nearestT) + " < t_min = " + num(e.t_min_node) +
             ": the node starts beyond the hit, so none of its primitives can be nearer. Skip it." +
             (after && after->type == EventType::hit_accepted
                  ? " Every node under it on the stack starts later still."
                  : "");
    }
    case EventType::prim_test: {
      std::string where = s.nodeEvent >= 0 ? " in leaf " + std::to_string(ev[size_t(s.nodeEvent)].node) : "";
      return explainPrimTest(trace, ray, e, s, where);
    }
    case EventType::mailbox_hit:
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim && m.leaf >= 0)
          return "Primitive " + std::to_string(e.prim) + " was already tested in leaf " +
                 std::to_string(m.leaf) +
                 " for this ray (it lies in several leaves): the mailbox skips the test." +
                 mailboxStamp(trace, ray, e.prim);
      return "Primitive " + std::to_string(e.prim) + " was already tested for this ray: skipped." +
             mailboxStamp(trace, ray, e.prim);
    case EventType::hit_accepted: {
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      if (e.reason == AcceptReason::next_node_beyond) {
        int pop = findEvent(ray, s.step, EventType::pop, false);
        std::string tmin = pop >= 0 ? num(ev[size_t(pop)].t_min_node) : "?";
        if (trace && trace->structure.kind == "bsp")
          return "Traverse until tmin(next node) > tmax(ray): every entry popped from the stack starts "
                 "beyond "
                 "the hit (the last one at t_min = " +
                 tmin + " > t(hit) = " + num(e.t) + ") and the stack is empty  =>  stop, the hit is final.";
        return "Traverse until tmin(next node) > tmax(ray):\ntmin(popped node) = " + tmin +
               " > t(hit) = " + num(e.t) +
               ", and every node below it on the stack starts later still  =>  stop, the hit is final.";
      }
      return "The stack is empty: every node the ray crosses has been visited. The nearest hit, t = " +
             num(e.t) + ", is final.";
    }
    case EventType::ray_end:
      if (e.prim < 0) return "Miss: the walk visited every node the ray crosses without a hit.";
      return "Result: primitive " + std::to_string(e.prim) + " at t = " + num(e.t) + ".";
    default:
      return "";
  }
}

// The decision at an inner BVH node once its children's boxes are tested: enter the nearer box hit, push the
// others, or (none hit) go on with the stack.
std::string bvhDecision(const BvhChoice& c) {
  std::vector<const BoxTestMark*> hits;
  for (const BoxTestMark& m : c.tests)
    if (m.hit) hits.push_back(&m);
  if (hits.empty())
    return "No child's box is hit: nothing under node " + std::to_string(c.node) +
           " can be hit. Go on with the next node on the stack.";
  const BoxTestMark* first = nullptr;
  for (const BoxTestMark* m : hits)
    if (m->child == c.first) first = m;
  if (hits.size() == 1)
    return "Only child " + std::to_string(hits[0]->child) + "'s box is hit: enter it, with [" +
           num(hits[0]->tNear) + ", " + num(hits[0]->tFar) + "].";
  std::string text = std::to_string(hits.size()) + " children's boxes are hit";
  // Overlapping intervals: the boxes overlap along the ray (bounding volumes can overlap).
  bool overlap = false;
  for (size_t a = 0; a < hits.size(); ++a)
    for (size_t b = a + 1; b < hits.size(); ++b)
      overlap |= hits[a]->tNear <= hits[b]->tFar && hits[b]->tNear <= hits[a]->tFar;
  if (overlap)
    text += ", and their intervals overlap: the boxes overlap along the ray (bounding volumes can overlap)";
  if (!first) return text + ".";
  bool byDistance = true;
  for (const BoxTestMark* m : hits) byDistance &= first->tNear <= m->tNear;
  text += ".\nNearer first: enter child " + std::to_string(first->child) + " (t_near = " + num(first->tNear) +
          ")";
  bool tie = false;
  for (const BoxTestMark* m : hits) tie |= m != first && m->tNear == first->tNear;
  text += !byDistance ? " (chosen by the ray's direction on the split axis, not by t_near)"
          : tie       ? " (a tie: the same t_near, so the child tested first goes first)"
                      : "";
  if (!c.pushed.empty()) {
    text += "; push ";
    for (size_t k = 0; k < c.pushed.size(); ++k) {
      if (k) text += ", ";
      text += "child " + std::to_string(c.pushed[k]);
      for (const BoxTestMark* m : hits)
        if (m->child == c.pushed[k]) text += " (t_near = " + num(m->tNear) + ")";
    }
    text += " for later.";
  } else {
    text += ".";
  }
  return text;
}

// The BVH's stack walk in the lecture's words: tight boxes, possibly overlapping, tested child by child.
std::string explainBvhRule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const std::vector<Event>& ev = ray.events;
  size_t next = size_t(s.step) + 1;
  const Event* after = next < ev.size() ? &ev[next] : nullptr;
  switch (e.type) {
    case EventType::ray_begin: {
      int first = findEvent(ray, 0, EventType::node, true);
      if (first < 0) return "The ray misses the root's box (slab test): no node to visit.";
      const Event& root = ev[size_t(first)];
      return "Slab test: the ray meets the root's box over [t_near, t_far] = [" + num(root.t_min_node) +
             ", " + num(root.t_max_node) + "]; the walk starts at the root.";
    }
    case EventType::node: {
      if (after && after->type == EventType::leaf)
        return "Node " + std::to_string(e.node) + " (depth " + std::to_string(e.depth) + ") is a leaf.";
      BvhChoice c = bvhChoice(ray, s);
      return "Inner " + nodeName(trace, e.node) + " (depth " + std::to_string(e.depth) +
             "), its box entered over [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "].\nTest its " +
             std::to_string(c.tests.size()) +
             " children's boxes (slab test). Each box is tight around its own primitives and may overlap its "
             "sibling's, so the ray may have to enter more than one.";
    }
    case EventType::box_test: {
      if (e.parent < 0)  // the root's own box, before the walk starts
        return e.hit ? "Slab test: the ray meets the root's box over [t_near, t_far] = [" +
                           num(e.t_min_node) + ", " + num(e.t_max_node) + "]; the walk starts at the root."
                     : std::string(
                           "The ray misses the root's box (slab test): nothing in the scene can be hit.");
      std::string text = "Child " + std::to_string(e.node) + " of node " + std::to_string(e.parent) + ": ";
      if (e.hit)
        text +=
            "its box is hit over [t_near, t_far] = [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "].";
      else
        text += s.nearestPrim >= 0
                    ? "its box is missed: the ray does not enter it before the nearest hit so far, t = " +
                          num(s.nearestT) + ", so nothing under it can give a nearer hit."
                    : std::string(
                          "its box is missed (the slab intervals do not overlap): nothing under it can "
                          "be hit.");
      BvhChoice c = bvhChoice(ray, s);
      if (c.valid && c.decided) text += "\n" + bvhDecision(c);
      return text;
    }
    case EventType::push:
      return "Push child " + std::to_string(e.node) + " with [t_near, t_far] = [" + num(e.t_min_node) + ", " +
             num(e.t_max_node) + "]: it waits while the nearer child is walked. The stack holds " +
             std::to_string(s.stack.size()) + (s.stack.size() == 1 ? " node." : " nodes.");
    case EventType::leaf: {
      size_t k = s.prims.size();
      std::string head =
          "Leaf " + std::to_string(e.node) + " over [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "]";
      if (k == 0) return head + " is empty: nothing to test. Go on with the next node on the stack.";
      return head + ": test its " + std::to_string(k) + (k == 1 ? " primitive" : " primitives") +
             ". No mailbox: in a BVH each primitive is in exactly one leaf, so no primitive is tested twice "
             "for a ray (the kd-tree needs mailboxes because it copies a primitive into every cell it "
             "overlaps).";
    }
    case EventType::pop: {
      std::string head = "Pop " + nodeName(trace, e.node) + " with t_near = " + num(e.t_min_node) + ". ";
      if (after && after->type == EventType::skip) return head + "Is its box beyond the nearest hit?";
      if (s.nearestPrim < 0) return head + "No hit yet: visit it.";
      return head + "The nearest hit so far, t = " + num(s.nearestT) +
             ", is not before its t_near: a nearer hit may lie in its box (the boxes overlap, or the hit "
             "lies "
             "beyond it), so visit it.";
    }
    case EventType::skip:
      return "skip: t_near = " + num(e.t_min_node) + " > t of the nearest hit = " + num(s.nearestT) +
             ": the box starts beyond the hit, so nothing in it can be nearer. Skip node " +
             std::to_string(e.node) + " without testing its children.";
    case EventType::prim_test: {
      std::string where = s.nodeEvent >= 0 ? " in leaf " + std::to_string(ev[size_t(s.nodeEvent)].node) : "";
      return explainPrimTest(trace, ray, e, s, where);
    }
    case EventType::hit_accepted: {
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      if (e.reason == AcceptReason::next_node_beyond) {
        int pop = findEvent(ray, s.step, EventType::pop, false);
        std::string tnear = pop >= 0 ? num(ev[size_t(pop)].t_min_node) : "?";
        return "The popped node starts beyond the hit: t_near = " + tnear + " > t(hit) = " + num(e.t) +
               ", and every node below it on the stack was skipped or starts later  =>  stop, the hit is "
               "final.";
      }
      return "The stack is empty: every box the ray entered has been walked or skipped. The nearest hit, t "
             "= " +
             num(e.t) + ", is final.";
    }
    case EventType::ray_end:
      if (e.prim < 0) return "Miss: the walk tested every box the ray enters without a hit.";
      return "Result: primitive " + std::to_string(e.prim) + " at t = " + num(e.t) + ".";
    default:
      return "";
  }
}

}  // namespace

std::string explainRule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  if (!s.event) return "";
  if (isBvhRay(trace, ray)) return explainBvhRule(trace, ray, s);
  if (isOctreeRay(trace, ray)) return explainOctreeRule(trace, ray, s);
  return isTreeRay(ray) ? explainTreeRule(trace, ray, s) : explainGridRule(trace, ray, s);
}

}  // namespace raystep::viz
