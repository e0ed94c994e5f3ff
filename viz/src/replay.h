// The replay model: what the debugger shows after the first `step + 1` events of one traced ray. Computed
// from the events alone (no scene, no structure), and from scratch for every step, so stepping back and
// forth always gives the same state. Plain C++ (no Qt, no VTK), like the trace it reads.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/trace/trace_file.h"

namespace raystep::viz {

// The state of a primitive referenced by the current cell (or, later, leaf).
enum class PrimState { pending, testing, hit, missed, skipped };
const char* primStateName(PrimState s);

struct PrimMark {
  int32_t prim = -1;
  PrimState state = PrimState::pending;
  float t = 0.f;  // for hit
  bool hit = false;  // a test's result, known at its own event: the one being tested is drawn with it
};

// One mailbox entry: a primitive tested for this ray, where and with what result.
struct MailboxEntry {
  int32_t prim = -1;
  int testedInCellEvent = -1;  // index of the cell event during which it was tested
  int cell[3] = {0, 0, 0};
  int32_t leaf = -1;  // trees: the leaf it was tested in
  bool hit = false;
  float t = 0.f;
  int skips = 0;  // mailbox hits so far
};

// Trees: an entry of the traversal stack (the far child pushed, with its interval).
struct StackEntry {
  int32_t node = -1;
  int32_t depth = 0;
  float tMin = 0.f, tMax = 0.f;
  int pushEvent = -1;  // index of the push event
};

// Trees: what the ray does at an inner node, in the lecture's words. t* is where the ray meets the split plane;
// the near child is the side the ray comes from as it moves along its direction (below the plane when the
// direction points up the axis, by the sign bit, as the kernel decides). Then only the near child is visited
// (t* > t_max: the ray leaves the node first), only the far one (t* < t_min: the node's part of the ray lies
// beyond the plane), or both: Intersect(near, t_min, t*) now and the far child (t*, t_max) pushed.
enum class Crossing { nearOnly, farOnly, both, inPlane };
const char* crossingName(Crossing c);
struct NodeCrossing {
  bool valid = false;  // false: no inner node now, or its split plane is not in the trace
  int nodeEvent = -1;
  int32_t node = -1;
  int axis = 0;
  float split = 0.f;
  float tStar = 0.f;  // NaN when the ray lies in the plane, +-inf when it runs parallel to it
  float tMin = 0.f, tMax = 0.f;
  bool nearIsBelow = true;  // the near child is the one below the plane
  Crossing crossing = Crossing::nearOnly;
  int32_t nearChild = -1, farChild = -1;  // -1: not visited from this node
  // A general BSP node (trace version 4): the plane dot(normal, p) = offset instead of axis and split. t* =
  // (offset - n.o) / (n.dir), by the kernel's bsp_crossing (double, with its error bound: [tLo, tHi] holds
  // the exact t*); originSide = n.o - offset (the origin's signed distance for a unit normal), nDotDir =
  // n.dir. Crossing::inPlane then means "parallel within rounding and on or too near the plane to tell".
  bool general = false;
  glm::vec3 normal{0.f};
  float offset = 0.f;
  double originSide = 0.0, nDotDir = 0.0;
  float tLo = 0.f, tHi = 0.f;
};

// Octree (Revelles, Ureña, Lastra 2000): the order of the current inner cell's children along the ray. The
// entry plane (the cell face the ray enters by: the largest of the three entry t's) picks the first child:
// on the entry axis the near half, on the others the half the ray is in at t_enter (their centre planes
// crossed before it or not). Each next child is the neighbour across the plane the ray leaves the child by
// (the smallest of its three exit t's); a cell face instead of a centre plane: the ray leaves the parent.
struct OctreeChildStep {
  int octant = 0;     // 0..7: bit 0 upper half in x, bit 1 y, bit 2 z (the trace's children order)
  int32_t node = -1;  // its id (from the trace's children list; -1 unknown)
  int exitAxis = 0;   // the plane it is left by
  float tExit = 0.f;
  bool leavesParent = false;  // that plane is the parent's face
};
struct OctreeChoice {
  bool valid = false;  // false: the current node is not an inner octree cell, or the trace has not its cell
  int nodeEvent = -1;
  int32_t node = -1;
  int depth = 0;
  float tEnter = 0.f, tExit = 0.f;  // the cell's part of the ray
  int entryAxis = -1;  // -1: the ray starts inside the cell (then t_enter is the ray's own start)
  float t0[3] = {0, 0, 0}, t1[3] = {0, 0, 0}, tMid[3] = {0, 0, 0};  // per axis: entry, exit, centre plane
  bool moving[3] = {true, true, true};                              // false: the direction's component is 0
  std::vector<OctreeChildStep> path;  // by the planes, as the lecture's algorithm walks them
  std::vector<int32_t> visited;       // the children the events visit under this cell, in order
  std::vector<int> visitedOctants;    // their octants (-1: not found among the children)
  int visitedSoFar = 0;               // how many of them are at or before the current event
};
struct ReplayState;
bool isOctreeRay(const Trace* trace, const TracedRay& ray);
// The current octree cell's child order (the node event of s.nodeEvent, or the push right after it).
OctreeChoice octreeChoice(const Trace& trace, const TracedRay& ray, const ReplayState& s);
// "x+ y- z+": an octant's halves (+ upper, - lower).
std::string octantName(int octant);

// BVH: one child's box tested from the current inner node (lecture: "bounding volumes can overlap", so the
// ray may enter more than one child). done: the test is at or before the current event.
struct BoxTestMark {
  int32_t child = -1;
  bool hit = false;
  float tNear = 0.f, tFar = 0.f;  // on a hit
  int event = -1;
  bool done = false;
};

// BVH: what the walk does at the current inner node: each child's box test ([t_near, t_far] or a miss), the
// child entered first (the nearer one hit) and the children pushed for later, from the events that follow the
// node event.
struct BvhChoice {
  bool valid = false;  // false: the current node is not an inner BVH node with box tests
  int nodeEvent = -1;
  int32_t node = -1;
  std::vector<BoxTestMark> tests;  // in the order the kernel tested them
  int32_t first = -1;              // the child walked next (-1: none hit, the walk pops)
  std::vector<int32_t> pushed;     // pushed, bottom first
  bool decided = false;            // the current event is the last box test or later: the choice is known
};

struct ReplayState {
  int step = -1;  // index of the current event
  const Event* event = nullptr;
  // Grid: the current cell event (index into events, -1: none yet) and the cells visited before it.
  int cellEvent = -1;
  std::vector<int> visitedCellEvents;
  // The current tree node: the last node, leaf or pop event (at a push it is still the inner node being split),
  // -1: none; and the stack: the pushes not yet popped, top last.
  int nodeEvent = -1;
  std::vector<StackEntry> stack;
  // The nodes the walk was at before the current one, each once, in the order it left them.
  std::vector<int32_t> visitedNodes;
  // BVH: popped entries not visited (their t_near beyond the nearest hit), in order.
  std::vector<int32_t> skippedNodes;
  // The primitives of the current cell (or leaf), the block of events from blockEvent to the next cell:
  // every one it references, in the order the walk meets them.
  int blockEvent = -1;
  std::vector<PrimMark> prims;
  std::vector<MailboxEntry> mailbox;  // in test order
  RayCounters counters;
  // The nearest hit so far and whether it is final.
  int32_t nearestPrim = -1;
  float nearestT = 0.f;
  bool deferred = false, accepted = false, ended = false;
  AcceptReason reason = AcceptReason::inside_cell;
  // The ray's current interval [tMin, tMax]: the cell's (grid) or the current node's (tree); valid when
  // hasInterval.
  bool hasInterval = false;
  float tMin = 0.f, tMax = 0.f;
};

ReplayState replayAt(const TracedRay& ray, int step);

// True when the ray walked a tree (node, push, pop, leaf, box_test or skip events).
bool isTreeRay(const TracedRay& ray);
// True when the ray walked a BVH: the trace's structure is a BVH ("bvh", "bvh-sweep", "bvh-median", "bvh4",
// "bvh8"), or (without a trace) its events test children's boxes.
bool isBvhKind(const std::string& kind);
bool isBvhRay(const Trace* trace, const TracedRay& ray);
// The BVH choice at the current inner node (the node event of s.nodeEvent).
BvhChoice bvhChoice(const TracedRay& ray, const ReplayState& s);
// The node of a trace's geometry with this id, or null.
const TraceNode* findNode(const Trace& trace, int32_t id);
// The crossing at the current inner node (the node event of s.nodeEvent), from the trace's split plane and the
// events that follow it.
NodeCrossing nodeCrossing(const Trace& trace, const TracedRay& ray, const ReplayState& s);

// Index of the next (forward) or previous event of `type` after/before `from`; -1 when there is none.
int findEvent(const TracedRay& ray, int from, EventType type, bool forward);
// Index of the k-th (1-based) event of `type`; -1 when there are fewer.
int nthEvent(const TracedRay& ray, EventType type, int k);

// One line describing an event, for the event list: "12  prim_test  prim 7: miss".
std::string describeEvent(const Event& e);
// Why the walk does what the current event shows, with its numbers: the 3D-DDA's axis, the tree's t* and
// children, the mailbox, and the stopping rule (grid: "tmin(cell) > tmax(ray)"; tree: the next node on the
// stack starts beyond the hit). `trace` gives the nodes' split planes (null: t* is not shown) and the primitives'
// vertices (null: a triangle's test is not compared with Möller–Trumbore).
std::string explainRule(const Trace* trace, const TracedRay& ray, const ReplayState& s);
inline std::string explainRule(const TracedRay& ray, const ReplayState& s) { return explainRule(nullptr, ray, s); }

// One line for a triangle's test (empty for another primitive): what the watertight test decides for this ray
// and triangle alone (up to the ray's own tmax) and how (float alone, the double-precision filter or exact
// rational arithmetic, by exact_counters()), and what Möller–Trumbore says, with the barycentric that rejects a
// miss: "... watertight hit (settled by exact rational arithmetic); Möller–Trumbore miss (v = -3e-08 < 0)."
std::string compareTriangleTests(const TracedRay& ray, const TracePrimitive& prim);

const char* axisName(int axis);  // "x", "y", "z", or "none" for -1

}  // namespace raystep::viz
