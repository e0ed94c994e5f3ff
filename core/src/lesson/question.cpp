// The quiz's questions (question.h): their names and prompts, the answers computed from the recorded walk or
// the build, and the check of a typed prediction. The Why of a walk's decision is the replay's own
// (replay/explain.h: what the state panel and `raystep replay` say at that event), so every sentence about a
// step exists once; the octree's next cell out of a leaf, the build's and the pixel's questions are worded
// here, where they are the only ones to say it.
#include "raystep/lesson/question.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/lesson/tree_nodes.h"
#include "raystep/render/antialiasing.h"
#include "raystep/render/camera.h"
#include "raystep/render/whitted.h"
#include "raystep/replay/explain.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/replay_state.h"
#include "raystep/report/bvol_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/node_path.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

struct KindInfo {
  QuestionKind kind;
  const char* name;
  const char* prompt;
};
constexpr KindInfo kKinds[] = {
    {QuestionKind::next_cell, "next-cell",
     "Which cell does the ray enter next (i,j,k), or does the walk stop?"},
    {QuestionKind::dda_axis, "dda-axis",
     "Along which axis does the 3D-DDA step out of this cell (x, y, z, or none)?"},
    {QuestionKind::first_child, "first-child",
     "Which child does the walk visit first (below or above the plane), and is the far child pushed?"},
    {QuestionKind::next_pop, "next-pop",
     "Which node is popped from the stack next, or does the walk stop here?"},
    {QuestionKind::sah_plane, "sah-plane",
     "Which plane does the SAH choose for this node (axis and position), or a leaf?"},
    {QuestionKind::subdivide, "subdivide",
     "Does adaptive sampling subdivide this pixel (more than its 5 first samples)?"},
    {QuestionKind::bvol_kind, "bvol-kind",
     "Which kind of bounding volume do the rays enter in vain least often: the box, the sphere, the 14-DOP "
     "or "
     "the oriented box?"},
};

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

// The Why of the walk's decision at `event`, as the debugger's state panel and `raystep replay` give it: each
// sentence about a step exists once, in replay/explain.
std::string walk_why(const QuestionContext& c, const TracedRay& r, int event) {
  return replay::explain_rule(c.trace, r, replay::replay_at(r, event));
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}
using replay::axis_name;
std::string cell_text(const int* c) {
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + ")";
}
std::string triple(const glm::vec3& v) {
  return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")";
}

bool is_tree_event(EventType t) {
  return t == EventType::node || t == EventType::push || t == EventType::pop || t == EventType::leaf;
}

// The current ray and event of the context; throws when the question needs a walk and there is none.
const TracedRay& current_ray(QuestionKind kind, const QuestionContext& c) {
  const std::string name = question_kind_name(kind);
  if (!c.trace || c.trace->rays.empty()) fail(name + ": no traced ray (choose a pixel: pixel: X,Y)");
  if (c.ray < 0 || size_t(c.ray) >= c.trace->rays.size()) fail(name + ": no ray " + std::to_string(c.ray));
  const TracedRay& r = c.trace->rays[size_t(c.ray)];
  if (c.step < 0 || size_t(c.step) >= r.events.size())
    fail(name + ": no event " + std::to_string(c.step) + " (the ray has " + std::to_string(r.events.size()) +
         ")");
  return r;
}

bool walks_tree(const TracedRay& r) {
  for (const Event& e : r.events)
    if (is_tree_event(e.type)) return true;
  return false;
}

// A BVH's walk tests its children's boxes: box_test events, which a kd-tree's walk never has.
bool walks_bvh(const TracedRay& r) {
  for (const Event& e : r.events)
    if (e.type == EventType::box_test) return true;
  return false;
}

// ---- The grid: next-cell and dda-axis, from the cell events (the kernel logs tMax per axis with each cell).

Answer grid_answer(QuestionKind kind, const QuestionContext& c) {
  const TracedRay& r = current_ray(kind, c);
  const std::string name = question_kind_name(kind);
  if (walks_tree(r)) fail(name + ": the ray walks a kd-tree, not a grid (accel: grid)");
  const std::vector<Event>& ev = r.events;
  int cell = -1;  // the current cell: the last cell event up to the current event
  for (int i = 0; i <= c.step; ++i)
    if (ev[size_t(i)].type == EventType::cell) cell = i;
  if (kind == QuestionKind::dda_axis && cell < 0)
    fail(name + ": the walk is in no cell yet at event " + std::to_string(c.step) +
         " (step to a cell event)");
  int next = -1;
  for (size_t i = size_t(cell + 1); i < ev.size() && next < 0; ++i)
    if (ev[i].type == EventType::cell) next = int(i);

  Answer a;
  a.kind = kind;
  a.stops = next < 0;
  if (next >= 0) std::copy(ev[size_t(next)].cell, ev[size_t(next)].cell + 3, a.cell.begin());
  if (cell < 0) {  // next-cell before the walk: the slab test's first cell, or a miss of the grid's box
    a.text = a.stops ? "the walk stops: the ray misses the grid" : "cell " + cell_text(a.cell.data());
    a.why = walk_why(c, r, 0);  // the ray_begin event: the slab test
    return a;
  }
  const Event& e = ev[size_t(cell)];
  if (next >= 0)
    for (int k = 0; k < 3; ++k)
      if (ev[size_t(next)].cell[k] != e.cell[k]) a.axis = k;
  const std::string step = !a.stops && r.ray.direction[a.axis] > 0.f ? "+1" : "-1";
  a.why = walk_why(c, r, cell);
  if (kind == QuestionKind::next_cell)
    a.text = a.stops
                 ? "the walk stops: there is no next cell"
                 : "cell " + cell_text(a.cell.data()) + ": the ray steps along " + axis_name(a.axis) + ".";
  else
    a.text = a.stops ? "none: the walk ends in this cell"
                     : std::string(axis_name(a.axis)) + ": the 3D-DDA steps " + axis_name(a.axis) + " by " +
                           step + " into cell " + cell_text(a.cell.data()) + ".";
  return a;
}

// ---- The kd-tree: first-child and next-pop, from the node, push and pop events.

using replay::find_node;

std::string side(bool below) {
  return below ? "below" : "above";
}

// ---- The octree (Revelles, Urena and Lastra): first-child and next-cell, from the node events, explained by
// the cells' planes as the kernel computes them (octree.h: float, by the direction's reciprocal).

bool walks_octree(const QuestionContext& c) {
  return c.trace && c.trace->structure.kind == "octree";
}

using replay::octant_name;

// 3: an octree cell's; 2: a quadtree's (a 2D scene's: four children, cut on x and y).
int axes_of(const TraceNode& parent) { return parent.children.size() == 4 ? 2 : 3; }

// Which of its parent's eight (a quadtree's four) children a cell is (-1: not found in the trace).
int octant_of(const Trace& trace, int32_t id, const TraceNode** parent) {
  const TraceNode* n = find_node(trace, id);
  *parent = n && n->parent >= 0 ? find_node(trace, n->parent) : nullptr;
  if (!*parent) return -1;
  for (size_t k = 0; k < (*parent)->children.size(); ++k)
    if ((*parent)->children[k] == id) return int(k);
  return -1;
}

std::string cell_name(const Trace& trace, int32_t id) {
  const TraceNode* parent = nullptr;
  const int octant = octant_of(trace, id, &parent);
  if (octant < 0) return "cell " + std::to_string(id);
  return "cell " + std::to_string(id) + " (" + octant_name(octant, axes_of(*parent)) + " of cell " +
         std::to_string(parent->id) + ")";
}

// A cell's planes along the ray: per axis the entry and exit t (in the direction of travel) and the centre
// plane's t; an axis the ray does not move along has -inf, +inf and the centre by the origin's side.
struct CellPlanes {
  float t0[3], t1[3], mid[3];
  bool moving[3];
  int entry = 0;  // the entry plane: the largest t0 (ties to the lower axis, as the kernel)
  float t_in = 0.f;
};
CellPlanes cell_planes(const Bounds3& box, const Ray& ray) {
  CellPlanes p;
  for (int a = 0; a < 3; ++a) {
    const float d = ray.direction[a], inv = 1.f / d, o = ray.origin[a];
    const bool neg = std::signbit(d);
    const float m = 0.5f * (box.lo[a] + box.hi[a]);  // the build's centre (octree_build.cpp)
    p.moving[a] = std::isfinite(inv);
    if (p.moving[a]) {
      p.t0[a] = ((neg ? box.hi[a] : box.lo[a]) - o) * inv;
      p.t1[a] = ((neg ? box.lo[a] : box.hi[a]) - o) * inv;
      p.mid[a] = (m - o) * inv;
    } else {
      p.t0[a] = -kInfinity;
      p.t1[a] = kInfinity;
      p.mid[a] = (o >= m) != neg ? -kInfinity : kInfinity;
    }
  }
  p.entry = p.t0[0] >= p.t0[1] && p.t0[0] >= p.t0[2] ? 0 : (p.t0[1] >= p.t0[2] ? 1 : 2);
  p.t_in = p.t0[p.entry];
  return p;
}

// "x at 2.1" per moving axis.
std::string planes_text(const float* t, const bool* moving) {
  std::string s;
  for (int a = 0; a < 3; ++a)
    if (moving[a]) s += std::string(s.empty() ? "" : ", ") + axis_name(a) + " at " + num(t[a]);
  return s.empty() ? "none" : s;
}

// The index of the first node event after `from` (or -1), and whether the walk's end comes first.
int next_node_event(const std::vector<Event>& ev, size_t from) {
  for (size_t i = from; i < ev.size(); ++i) {
    if (ev[i].type == EventType::node) return int(i);
    if (ev[i].type == EventType::hit_accepted || ev[i].type == EventType::ray_end) return -1;
  }
  return -1;
}

// The answer's cell: the node, its octant, the text.
void set_octree_cell(Answer& a, const Trace& trace, int32_t id) {
  const TraceNode* parent = nullptr;
  a.node = id;
  a.first_child = id;
  a.octant = octant_of(trace, id, &parent);
  a.axes = parent ? axes_of(*parent) : 3;
  a.stops = false;
  a.text = a.octant >= 0 ? octant_name(a.octant, axes_of(*parent)) + " (node " + std::to_string(id) + ", a child of cell " +
                               std::to_string(parent->id) + ")"
                         : "node " + std::to_string(id);
}

// The current event at an inner cell: its node event or the push right after it.
Answer octree_first_child(QuestionKind kind, const QuestionContext& c, int node_event) {
  const TracedRay& r = c.trace->rays[size_t(c.ray)];
  const std::vector<Event>& ev = r.events;
  const Event& e = ev[size_t(node_event)];
  const TraceNode* n = find_node(*c.trace, e.node);
  if (!n || n->leaf || n->children.size() != 8)
    fail(std::string(question_kind_name(kind)) + ": the trace has not the children of cell " +
         std::to_string(e.node));
  const int first = next_node_event(ev, size_t(node_event) + 1);
  if (first < 0)
    fail(std::string(question_kind_name(kind)) + ": the walk does not go on from cell " +
         std::to_string(e.node));
  Answer a;
  a.kind = kind;
  a.walk = "octree";
  set_octree_cell(a, *c.trace, ev[size_t(first)].node);

  a.why = walk_why(c, r, node_event);
  return a;
}

Answer octree_answer(QuestionKind kind, const QuestionContext& c) {
  const TracedRay& r = current_ray(kind, c);
  const std::string name = question_kind_name(kind);
  const std::vector<Event>& ev = r.events;
  // The cell the walk is at: the last node event up to the current event.
  int at = -1;
  for (int i = 0; i <= c.step; ++i)
    if (ev[size_t(i)].type == EventType::node) at = i;
  const bool inner = at >= 0 && size_t(at) + 1 < ev.size() && ev[size_t(at) + 1].type == EventType::push &&
                     ev[size_t(at) + 1].node == ev[size_t(at)].node;
  if (kind == QuestionKind::first_child) {
    const bool here = at >= 0 && (c.step == at || (inner && c.step == at + 1));
    if (!here || !inner)
      fail("first-child: the walk is not at an inner cell at event " + std::to_string(c.step) + " (a " +
           event_type_name(ev[size_t(c.step)].type) + " event; step-to: node:K at a cell with children)");
    return octree_first_child(kind, c, at);
  }
  // next-cell: the cell the walk enters next.
  if (at >= 0 && inner && c.step <= at + 1) return octree_first_child(kind, c, at);
  Answer a;
  a.kind = kind;
  a.walk = "octree";
  const size_t after = size_t(std::max(at, c.step)) + 1;
  const int next = next_node_event(ev, after);
  const Event* accepted = nullptr;
  for (size_t i = after; i < ev.size() && !accepted; ++i)
    if (ev[i].type == EventType::hit_accepted) accepted = &ev[i];
  if (next >= 0) {
    set_octree_cell(a, *c.trace, ev[size_t(next)].node);
  } else {
    a.stops = true;
    a.text = "the walk stops: there is no next cell";
  }
  if (at < 0) {  // before the walk: the root cube, or a miss
    a.why = a.stops ? "Slab test: the ray misses the octree's root cube: no cell to visit."
                    : "Slab test: the ray meets the root cube at t = " + num(ev[size_t(next)].t_min_node) +
                          ": the walk starts at the root, cell " + std::to_string(a.node) + ".";
    if (!a.stops) a.text = "node " + std::to_string(a.node) + " (the root)";
    return a;
  }
  const Event& e = ev[size_t(at)];
  const TraceNode* n = find_node(*c.trace, e.node);
  if (!n) fail(name + ": the trace has not cell " + std::to_string(e.node));
  // The cell's exit plane: the smallest exit t (ties to the lower axis, as the kernel).
  const CellPlanes p = cell_planes(n->box, r.ray);
  const int exit = p.t1[0] <= p.t1[1] && p.t1[0] <= p.t1[2] ? 0 : (p.t1[1] <= p.t1[2] ? 1 : 2);
  const bool grazed = e.t_max_node <= e.t_min_node;  // a point: walked for rounding's sake (octree.h)
  std::string w =
      grazed ? "The ray only grazes cell " + std::to_string(e.node) + " (its interval [" + num(e.t_min_node) +
                   ", " + num(e.t_max_node) +
                   "] is a point; the walk visits it so that rounding never skips a cell the exact ray "
                   "touches). "
             : "Cell " + std::to_string(e.node) + " is left at t_exit = " + num(e.t_max_node) +
                   " through its face normal to " + axis_name(exit) +
                   " (exit t: " + planes_text(p.t1, p.moving) + "; the smallest). ";
  if (accepted && accepted->reason == AcceptReason::any_hit) {
    a.why = "A shadow ray stops at its first hit, t = " + num(accepted->t) + ": the walk ends in cell " +
            std::to_string(e.node) + ".";
    return a;
  }
  if (a.stops && accepted && accepted->reason == AcceptReason::inside_cell) {
    a.why = w + "The hit at t = " + num(accepted->t) + " (primitive " + std::to_string(accepted->prim) +
            ") lies inside this cell: every later cell starts at t >= " + num(e.t_max_node) +
            " > tmax(ray) = " + num(accepted->t) +
            ", so the walk stops (traverse until tmin(cell) > tmax(ray)).";
    return a;
  }
  if (a.stops && accepted && accepted->reason == AcceptReason::next_node_beyond) {
    a.why = w + "The next cell would start at t = " + num(e.t_max_node) +
            ", beyond the nearest hit, t = " + num(accepted->t) +
            ": tmin(cell) > tmax(ray), the walk stops with that hit.";
    return a;
  }
  if (a.stops) {
    a.why =
        w + "That face is the root cube's own: the ray leaves the octree" +
        (accepted ? " with its nearest hit, t = " + num(accepted->t) + "." : std::string(" without a hit."));
    return a;
  }
  // Across the exit plane: the sibling, or (the face is the parent's too) the parent is done.
  const TraceNode* parent = nullptr;
  const int octant = octant_of(*c.trace, e.node, &parent);
  const bool forward = !std::signbit(r.ray.direction[exit]);
  int pops = 0;
  for (size_t i = after; i < size_t(next); ++i) pops += ev[i].type == EventType::pop;
  const Event& to = ev[size_t(next)];
  if (grazed) {
    w += "The walk goes on with the next cell in entry order, " + cell_name(*c.trace, a.node) + ".";
  } else if (octant >= 0 && exit < axes_of(*parent) && pops == 0 &&
             parent->children[size_t(octant ^ (1 << exit))] == a.node) {
    w += "Across it lies its sibling " + octant_name(a.octant, axes_of(*parent)) + ", node " + std::to_string(a.node) +
         ": Revelles' table sends the walk from one child to the next by the plane it leaves by.";
  } else if (octant >= 0 && bool((octant >> exit) & 1) == forward && pops > 0) {
    w += "That face is also the face of cell " + std::to_string(parent->id) +
         std::string(pops > 1 ? " and of its parent" : "") + ": its children are done (" +
         std::to_string(pops) + (pops == 1 ? " pop" : " pops") + "), and the walk goes on in " +
         cell_name(*c.trace, a.node) + ", the next child across that plane.";
  } else {
    w += "The walk goes on in " + cell_name(*c.trace, a.node) + ".";
  }
  if (to.t_max_node <= to.t_min_node)
    w += " The ray only grazes that cell (its interval [" + num(to.t_min_node) + ", " + num(to.t_max_node) +
         "] is a point): the walk visits such a cell too, so that rounding never skips a cell the exact ray "
         "touches.";
  else if (!grazed)
    w += " It begins where this cell ends, at t = " + num(to.t_min_node) + ".";
  else
    w += " It begins at t = " + num(to.t_min_node) + ".";
  const Event* deferred = nullptr;
  for (size_t i = size_t(at); i < size_t(next) && !deferred; ++i)
    if (ev[i].type == EventType::hit_deferred) deferred = &ev[i];
  if (deferred)
    w += " The hit found here, t = " + num(deferred->t) +
         ", lies beyond this cell's exit: kept, not accepted, "
         "as a later cell may hold a nearer one.";
  a.why = w;
  return a;
}

// ---- first-child on a kd-tree or a general BSP tree (bsp.h), next-pop on every tree.

// "node 2 (LL)": the trace's id and the path in the slides' notation (none for a wide BVH's node).
std::string node_named(const Trace* trace, int32_t id) {
  const std::string path = trace ? trace_node_path_text(*trace, id) : "";
  return "node " + std::to_string(id) + (path.empty() ? "" : " (" + path + ")");
}

Answer first_child_answer(const QuestionContext& c) {
  const TracedRay& r = current_ray(QuestionKind::first_child, c);
  const std::vector<Event>& ev = r.events;
  const Event& e = ev[size_t(c.step)];
  const size_t next = size_t(c.step) + 1;
  if (e.type != EventType::node)
    fail(std::string("first-child: event ") + std::to_string(c.step) + " is a " + event_type_name(e.type) +
         " event, not a node (step-to: node:K at an inner node)");
  if (next >= ev.size() || ev[next].type == EventType::leaf)
    fail("first-child: node " + std::to_string(e.node) + " is a leaf, not an inner node");
  const TraceNode* n = c.trace ? find_node(*c.trace, e.node) : nullptr;
  if (walks_bvh(r))
    fail(
        "first-child: asks which side of a kd-tree's split plane comes first; a BVH has no split plane "
        "(accel: kd or kd-median; on a BVH ask next-pop)");
  if (!n || n->leaf) fail("first-child: the trace has no split plane for node " + std::to_string(e.node));

  Answer a;
  a.kind = QuestionKind::first_child;
  size_t first = next;
  if (ev[next].type == EventType::push) {
    a.far_pushed = true;
    a.far_child = ev[next].node;
    first = next + 1;
  }
  if (first >= ev.size() || ev[first].type != EventType::node)
    fail("first-child: the walk does not go on from node " + std::to_string(e.node));
  a.first_child = ev[first].node;
  a.first_is_below = a.first_child == e.node + 1;  // depth-first order: the child below follows its parent
  if (c.trace) {
    a.first_child_path = trace_node_path_text(*c.trace, a.first_child);
    if (a.far_pushed) a.far_child_path = trace_node_path_text(*c.trace, a.far_child);
  }
  auto named = [](int32_t id, const std::string& path) {
    return "node " + std::to_string(id) + (path.empty() ? "" : ", " + path);
  };
  if (n->has_plane) {  // a BSP tree's node: a plane of any orientation
    a.walk = "bsp";
    a.why = walk_why(c, r, c.step);
    a.text = side(a.first_is_below) + " (" + named(a.first_child, a.first_child_path) + ")" +
             (a.far_pushed ? ", the far child, " + named(a.far_child, a.far_child_path) + ", is pushed"
                           : ", nothing is pushed");
    return a;
  }

  a.why = walk_why(c, r, c.step);
  a.text = side(a.first_is_below) + " (" + named(a.first_child, a.first_child_path) + ")" +
           (a.far_pushed ? ", the far child, " + named(a.far_child, a.far_child_path) + ", is pushed"
                         : ", nothing is pushed");
  return a;
}

Answer next_pop_answer(const QuestionContext& c) {
  const TracedRay& r = current_ray(QuestionKind::next_pop, c);
  const std::vector<Event>& ev = r.events;
  if (!walks_tree(r)) fail("next-pop: the ray walks a grid, not a tree (accel: kd, kd-median or a BVH)");
  if (walks_octree(c))
    fail(
        "next-pop: the octree keeps no stack of far children; its next cell follows from the exit plane "
        "(ask: next-cell)");
  // The leaf the walk is in: the current event is a leaf's node event, the leaf event or one of its tests.
  int leaf = -1;
  if (ev[size_t(c.step)].type == EventType::node && size_t(c.step) + 1 < ev.size() &&
      ev[size_t(c.step) + 1].type == EventType::leaf)
    leaf = c.step + 1;
  for (int i = c.step; i >= 0 && leaf < 0; --i) {
    EventType t = ev[size_t(i)].type;
    if (t == EventType::leaf)
      leaf = i;
    else if (is_tree_event(t))
      break;
  }
  if (leaf < 0)
    fail(std::string("next-pop: the walk is not in a leaf at event ") + std::to_string(c.step) + " (a " +
         event_type_name(ev[size_t(c.step)].type) + " event; step to a leaf or its tests)");

  // The stack when the leaf is reached, and the nearest hit once its tests are done (ties to the lower id).
  std::vector<const Event*> stack;
  for (int i = 0; i < leaf; ++i) {
    if (ev[size_t(i)].type == EventType::push) stack.push_back(&ev[size_t(i)]);
    if (ev[size_t(i)].type == EventType::pop && !stack.empty()) stack.pop_back();
  }
  size_t after = size_t(leaf) + 1;  // the first event after the leaf's tests
  while (after < ev.size() &&
         (ev[after].type == EventType::prim_test || ev[after].type == EventType::mailbox_hit))
    ++after;
  int32_t hit_prim = -1;
  float hit_t = 0.f;
  for (size_t i = 0; i < after; ++i) {
    const Event& t = ev[i];
    if (t.type != EventType::prim_test || !t.hit) continue;
    if (hit_prim >= 0 && (t.t > hit_t || (t.t == hit_t && t.prim > hit_prim))) continue;
    hit_prim = t.prim;
    hit_t = t.t;
  }

  // What the walk did next: the first popped node it visits, or the end (a pop skipped, a shadow ray's hit).
  Answer a;
  a.kind = QuestionKind::next_pop;
  a.stops = true;
  bool any_hit = false;
  for (size_t i = after; i < ev.size(); ++i) {
    if (ev[i].type == EventType::hit_accepted) {
      any_hit = ev[i].reason == AcceptReason::any_hit;
      break;
    }
    if (ev[i].type == EventType::skip) continue;  // a BVH's popped entry beyond the hit: the walk goes on
    if (ev[i].type != EventType::pop) break;
    if (i + 1 < ev.size() && ev[i + 1].type == EventType::skip) continue;
    if (i + 1 < ev.size() && ev[i + 1].type == EventType::node && ev[i + 1].node == ev[i].node) {
      a.stops = false;
      a.node = ev[i].node;
      break;
    }
  }

  // Why: the leaf's result and the stack, then the replay's Why of each event up to the decision (the pops,
  // a BVH's skips, the walk's end), as the state panel gives them one step at a time.
  const std::string hit = hit_prim >= 0 ? "the nearest hit so far, t = " + num(hit_t) + " (primitive " +
                                              std::to_string(hit_prim) + ")"
                                        : "no hit yet";
  std::string w = "Leaf " + node_named(c.trace, ev[size_t(leaf)].node).substr(5) + " done with " + hit + ".";
  if (!any_hit)
    w += stack.empty() ? " The stack is empty."
                       : " The stack holds " + std::to_string(stack.size()) +
                             (stack.size() == 1 ? " node." : " nodes.");
  for (size_t i = after; i < ev.size(); ++i) {
    const EventType t = ev[i].type;
    if (t != EventType::pop && t != EventType::skip && t != EventType::hit_accepted &&
        t != EventType::ray_end)
      break;
    w += "\n" + walk_why(c, r, int(i));
    const bool visited = t == EventType::pop && i + 1 < ev.size() && ev[i + 1].type == EventType::node &&
                         ev[i + 1].node == ev[i].node;
    if (visited || t == EventType::hit_accepted || t == EventType::ray_end) break;
  }
  a.why = w;
  if (!a.stops && c.trace) a.node_path = trace_node_path_text(*c.trace, a.node);
  a.text = a.stops ? "the walk stops here"
                   : "node " + std::to_string(a.node) +
                         (a.node_path.empty() ? "" : " (" + a.node_path + ")") + " is popped and visited";
  return a;
}

// ---- The build: sah-plane, from the node's SAH curve (the builder rerun with a listener on that node).

Answer sah_plane_answer(const QuestionContext& c) {
  const KdTree* kd = dynamic_cast<const KdTree*>(c.accel);
  if (!kd) fail("sah-plane: no kd-tree (accel: kd or kd-median)");
  const KdTreeData& tree = kd->data();
  if (c.node < 0 || size_t(c.node) >= tree.nodes.size())
    fail("sah-plane: no node selected (node: ID, node-path: LR... or panel: sah)");
  if (tree.nodes[size_t(c.node)].is_leaf())
    fail("sah-plane: node " + std::to_string(c.node) + " is a leaf (select an inner node)");
  const SahCurve curve = record_sah_curve(kd->geometry(), kd->options(), uint32_t(c.node));
  Answer a;
  a.kind = QuestionKind::sah_plane;
  a.node = c.node;
  a.axis = curve.leaf ? -1 : curve.axis;
  a.position = curve.position;
  if (a.axis >= 0) {
    a.extent = curve.info.box.hi[a.axis] - curve.info.box.lo[a.axis];
    a.lo = curve.info.box.lo[a.axis];
  }
  const KdOptions& o = kd->options();
  const std::string head = "Node " + std::to_string(c.node) + " holds N = " + std::to_string(curve.n_prims) +
                           " primitives; a leaf would cost N t_i = " + std::to_string(curve.n_prims) + " x " +
                           num(o.t_i) + " = " + num(curve.leaf_cost) + ". ";
  if (a.axis < 0) {
    a.text = "a leaf";
    a.why = head + "No plane costs less (" + leaf_reason_name(curve.leaf_reason) + "): the node is a leaf.";
    return a;
  }
  a.text = std::string(axis_name(a.axis)) + " = " + num(a.position);
  std::string formula;
  if (curve.chosen >= 0) {
    const SahCandidate& s = curve.candidates[size_t(curve.chosen)];
    const double pa = double(s.area_above) / s.area_node, pb = double(s.area_below) / s.area_node;
    const bool bonus = o.empty_bonus > 0.f && (s.n_above == 0 || s.n_below == 0);
    formula = "C = t_t + " + std::string(bonus ? "(1 - " + num(o.empty_bonus) + ") (" : "") +
              "p_a N_a t_i + p_b N_b t_i" + (bonus ? ")" : "") + " = " + num(o.t_t) + " + " +
              (bonus ? num(1.0 - o.empty_bonus) + " x (" : "") + num(pa) + " x " + std::to_string(s.n_above) +
              " x " + num(o.t_i) + " + " + num(pb) + " x " + std::to_string(s.n_below) + " x " + num(o.t_i) +
              (bonus ? ")" : "") + " = " + num(s.cost);
  } else {
    formula = "C = " + num(curve.cost);
  }
  if (o.builder == KdBuilder::median)
    a.why = head + "The spatial-median builder cuts the node's longest axis in the middle, " + a.text +
            ", whatever it costs: " + formula + ".";
  else
    a.why = head + "Of " + std::to_string(curve.candidates.size()) + " candidate planes the cheapest is " +
            a.text + ": " + formula + " < " + num(curve.leaf_cost) + ", so the SAH splits there.";
  return a;
}

// ---- The picture: subdivide, from the adaptive sampler run on the pixel with the renderer's radiance.

Answer subdivide_answer(const QuestionContext& c) {
  if (!c.scene || !c.accel) fail("subdivide: no scene");
  const AntiAliasing aa = c.aa.empty() ? c.scene->render.aa : parse_antialiasing(c.aa);
  if (aa.mode != AntiAliasing::Mode::adaptive)
    fail("subdivide: the picture's anti-aliasing is " + to_string(aa) +
         ", not adaptive (aa: adaptive:T[:D])");
  const int x = c.pixel[0], y = c.pixel[1];
  if (c.width < 1 || c.height < 1 || x < 0 || y < 0 || x >= c.width || y >= c.height)
    fail("subdivide: pixel " + std::to_string(x) + "," + std::to_string(y) + " lies outside the " +
         std::to_string(c.width) + "x" + std::to_string(c.height) + " picture");
  // The renderer's radiance: the Whitted tracer along the camera's ray through a raster position.
  const ProjectiveCamera camera(c.scene->camera, c.width, c.height);
  const WhittedTracer tracer(*c.scene, *c.accel);
  RayCounts counts;
  const RadianceFn radiance = [&](float px, float py) {
    return tracer.trace_primary(camera.generate(px, py), &counts);
  };
  Pcg32 rng(c.scene->render.seed, uint64_t(y) * uint64_t(c.width) + uint64_t(x));
  const PixelEstimate e = estimate_pixel(aa, x, y, rng, radiance);

  // The first level's five samples, where the sampler takes them: the corners and the centre.
  const float fx = float(x), fy = float(y);
  const glm::vec3 v[5] = {radiance(fx, fy), radiance(fx + 1.f, fy), radiance(fx, fy + 1.f),
                          radiance(fx + 1.f, fy + 1.f), radiance(fx + 0.5f, fy + 0.5f)};
  glm::vec3 contrast(0.f);
  for (int ch = 0; ch < 3; ++ch) {
    float lo = v[0][ch], hi = v[0][ch];
    for (const glm::vec3& s : v) lo = std::min(lo, s[ch]), hi = std::max(hi, s[ch]);
    contrast[ch] = hi + lo > 0.f ? (hi - lo) / (hi + lo) : 0.f;
  }
  const bool exceeds = contrast_exceeds(v, 5, aa.threshold);
  Answer a;
  a.kind = QuestionKind::subdivide;
  a.samples = e.samples;
  a.subdivided = e.samples > 5;
  const std::string head =
      "The 5 first samples (the 4 corners and the centre) have contrast (max - min) / "
      "(max + min) = " +
      triple(contrast) + " in (r, g, b); the threshold is T = " + num(aa.threshold) + ". ";
  if (aa.max_depth == 0)
    a.why = head + "With D = 0 levels the pixel is never split: 5 samples.";
  else if (exceeds)
    a.why =
        head +
        "A channel exceeds it, so the pixel is split into 4 quadrants and refined the same way, at most " +
        std::to_string(aa.max_depth) + " levels deep: " + std::to_string(e.samples) + " samples in all.";
  else
    a.why = head + "No channel exceeds it: the pixel keeps its 5 samples.";
  a.text = a.subdivided ? "yes: " + std::to_string(e.samples) + " samples" : "no: 5 samples";
  return a;
}

// ---- The bounding volumes: bvol-kind, from the bounding-volume report on the scene's camera rays.

// A kind in the lecture's words, and the report's name for it.
struct VolumeKind {
  const char* report;
  const char* words;
};
constexpr VolumeKind kVolumes[] = {{"bvol", "the box"},
                                   {"bvol-sphere", "the sphere"},
                                   {"bvol-kdop", "the 14-DOP"},
                                   {"bvol-obb", "the oriented box"}};
const char* volume_words(const std::string& report) {
  for (const VolumeKind& v : kVolumes)
    if (report == v.report) return v.words;
  return "?";
}

Answer bvol_kind_answer(const QuestionContext& c) {
  if (!c.scene) fail("bvol-kind: no scene");
  BvolReportOptions o;
  o.reps = 1;  // the counts do not depend on the timing passes
  const std::vector<BvolReportRow> rows = run_bvol_report(*c.scene, o);
  if (rows.empty()) fail("bvol-kind: the bounding-volume report measured nothing");
  double fewest = rows.front().false_positives_per_ray;
  for (const BvolReportRow& r : rows) fewest = std::min(fewest, r.false_positives_per_ray);
  Answer a;
  a.kind = QuestionKind::bvol_kind;
  std::string per;
  for (const BvolReportRow& r : rows) {
    // A tie within the report's rounding (two kinds fit the same objects alike) accepts both.
    if (r.false_positives_per_ray <= fewest + 1e-9 * std::max(1.0, fewest)) a.volumes.push_back(r.kind);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s %.3g in vain of %.3g entered (%.1f%%)", volume_words(r.kind),
                  r.false_positives_per_ray, r.entered_per_ray, 100.0 * r.false_positive_rate);
    per += (per.empty() ? "" : "; ") + std::string(buf);
  }
  for (const std::string& v : a.volumes)
    a.text += (a.text.empty() ? "" : " and ") + std::string(volume_words(v));
  a.text += a.volumes.size() == 1 ? ": it is entered in vain least often" : ": they tie";
  a.why = "Per ray, over " + std::to_string(rows.front().rays) + " camera rays (one per pixel): " + per +
          ". A volume is entered in vain when the ray enters it but misses the object inside: the emptier "
          "the space a kind encloses around the objects, the more often.";
  return a;
}

std::string normalised(const std::string& s) {
  std::string out;
  for (char ch : s)
    if (!std::isspace(static_cast<unsigned char>(ch)))
      out += char(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

// A node's path as typed (normalised: lower case): L and R letters, or "root"; a BVH's the same.
bool is_path(const std::string& s) {
  if (s == "root") return true;
  return !s.empty() && s.find_first_not_of("lr") == std::string::npos;
}

bool parse_whole(const std::string& s, long long* v) {
  if (s.empty() || s.size() > 12) return false;
  size_t i = s[0] == '-' ? 1 : 0;
  if (i == s.size()) return false;
  for (size_t k = i; k < s.size(); ++k)
    if (!std::isdigit(static_cast<unsigned char>(s[k]))) return false;
  *v = std::stoll(s);
  return true;
}

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    size_t comma = s.find(',', start);
    parts.push_back(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

int axis_of(const std::string& s) {
  return s == "x" ? 0 : s == "y" ? 1 : s == "z" ? 2 : -2;
}

}  // namespace

Answer answer_question(QuestionKind kind, const QuestionContext& context) {
  switch (kind) {
    case QuestionKind::next_cell:
      if (walks_octree(context)) return octree_answer(kind, context);
      return grid_answer(kind, context);
    case QuestionKind::dda_axis:
      if (walks_octree(context))
        fail(
            "dda-axis: the octree's walk has no 3D-DDA; its next cell follows from the exit plane (ask: "
            "next-cell)");
      return grid_answer(kind, context);
    case QuestionKind::first_child:
      if (walks_octree(context)) return octree_answer(kind, context);
      return first_child_answer(context);
    case QuestionKind::next_pop:
      return next_pop_answer(context);
    case QuestionKind::sah_plane:
      return sah_plane_answer(context);
    case QuestionKind::subdivide:
      return subdivide_answer(context);
    case QuestionKind::bvol_kind:
      return bvol_kind_answer(context);
  }
  fail("unknown question");
}

bool prediction_matches(const Answer& answer, const std::string& prediction) {
  const std::string p = normalised(prediction);
  const std::string name = question_kind_name(answer.kind);
  auto bad = [&](const std::string& expected) -> bool {
    fail(name + " '" + prediction + "': expected " + expected);
  };
  long long v = 0;
  if (answer.walk == "octree" &&
      (answer.kind == QuestionKind::next_cell || answer.kind == QuestionKind::first_child)) {
    // A cell: its node id or its octant within its parent ("x+y-z+"); next-cell also "stop".
    const bool quad = answer.axes == 2;  // a 2D scene's quadtree: quadrants, x and y only
    const std::string cell = quad ? "a quadrant such as x+y-" : "an octant such as x+y-z+";
    const std::string forms = answer.kind == QuestionKind::next_cell ? "a node id, " + cell + ", or stop"
                                                                     : "a node id or " + cell;
    if (p == "stop" && answer.kind == QuestionKind::next_cell) return answer.stops;
    if (parse_whole(p, &v)) return !answer.stops && v == answer.node;
    if (quad ? p.size() == 4 && p[0] == 'x' && p[2] == 'y' : p.size() == 6 && p[0] == 'x' && p[2] == 'y' && p[4] == 'z') {
      int octant = 0;
      for (int k = 0; k < answer.axes; ++k) {
        const char sign = p[size_t(2 * k + 1)];
        if (sign != '+' && sign != '-') return bad(forms);
        octant |= int(sign == '+') << k;
      }
      return !answer.stops && octant == answer.octant;
    }
    return bad(forms);
  }
  switch (answer.kind) {
    case QuestionKind::next_cell: {
      if (p == "stop") return answer.stops;
      std::string q = p;
      if (q.size() >= 2 && q.front() == '(' && q.back() == ')') q = q.substr(1, q.size() - 2);
      std::vector<std::string> parts = split_commas(q);
      long long c[3];
      if (parts.size() != 3) return bad("i,j,k or stop");
      for (int k = 0; k < 3; ++k)
        if (!parse_whole(parts[size_t(k)], &c[k])) return bad("i,j,k or stop");
      return !answer.stops && c[0] == answer.cell[0] && c[1] == answer.cell[1] && c[2] == answer.cell[2];
    }
    case QuestionKind::dda_axis:
      if (p == "none") return answer.axis < 0;
      if (axis_of(p) < 0) return bad("x, y, z or none");
      return answer.axis == axis_of(p);
    case QuestionKind::first_child: {
      std::vector<std::string> parts = split_commas(p);
      if (parts.size() > 2) return bad("below, above or a node id, optionally followed by ,push or ,no push");
      bool match;
      if (parts[0] == "below")
        match = answer.first_is_below;
      else if (parts[0] == "above")
        match = !answer.first_is_below;
      else if (parse_whole(parts[0], &v))
        match = v == answer.first_child;
      else if (is_path(parts[0]) && !answer.first_child_path.empty())
        match = parts[0] == normalised(answer.first_child_path);
      else
        return bad("below, above, a node id or its path (LR), optionally followed by ,push or ,no push");
      if (parts.size() == 2) {
        if (parts[1] == "push")
          match = match && answer.far_pushed;
        else if (parts[1] == "nopush")
          match = match && !answer.far_pushed;
        else
          return bad("below, above or a node id, optionally followed by ,push or ,no push");
      }
      return match;
    }
    case QuestionKind::next_pop:
      if (p == "stop") return answer.stops;
      if (is_path(p) && !answer.node_path.empty()) return !answer.stops && p == normalised(answer.node_path);
      if (!parse_whole(p, &v)) return bad("a node id, its path (LLR) or stop");
      return !answer.stops && v == answer.node;
    case QuestionKind::sah_plane: {
      if (p == "leaf") return answer.axis < 0;
      std::vector<std::string> parts = split_commas(p);
      const char* forms =
          "x, y or z, optionally ,POSITION (world units) or ,PERCENT% (across the node), or leaf";
      if (parts.size() > 2 || axis_of(parts[0]) < 0) return bad(forms);
      if (answer.axis != axis_of(parts[0])) return false;
      if (parts.size() == 1) return true;
      const bool percent = parts[1].size() > 1 && parts[1].back() == '%';
      const std::string number = percent ? parts[1].substr(0, parts[1].size() - 1) : parts[1];
      char* end = nullptr;
      double pos = std::strtod(number.c_str(), &end);
      if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(pos)) return bad(forms);
      if (percent) {  // the chart's axis: a reading off the chart, within 2% of the node
        if (!(answer.extent > 0.f)) return false;
        const double fraction = (double(answer.position) - double(answer.lo)) / double(answer.extent);
        return std::fabs(pos / 100.0 - fraction) <= 0.02;
      }
      double tolerance = 1e-4 * (answer.extent > 0.f ? double(answer.extent)
                                                     : std::max(1.0, std::fabs(double(answer.position))));
      return std::fabs(pos - double(answer.position)) <= tolerance;
    }
    case QuestionKind::subdivide:
      if (p == "yes") return answer.subdivided;
      if (p == "no") return !answer.subdivided;
      return bad("yes or no");
    case QuestionKind::bvol_kind: {
      const std::string kind =
          p == "box" || p == "aabb" || p == "bvol"                                         ? "bvol"
          : p == "sphere" || p == "bvol-sphere"                                            ? "bvol-sphere"
          : p == "14-dop" || p == "kdop" || p == "k-dop" || p == "dop" || p == "bvol-kdop" ? "bvol-kdop"
          : p == "orientedbox" || p == "obb" || p == "oriented" || p == "bvol-obb"         ? "bvol-obb"
                                                                                           : "";
      if (kind.empty()) return bad("box, sphere, 14-dop or oriented box");
      return std::find(answer.volumes.begin(), answer.volumes.end(), kind) != answer.volumes.end();
    }
  }
  return false;
}

std::string prediction_feedback(const Answer& answer, const std::string& prediction) {
  if (prediction_matches(answer, prediction)) return "";
  const std::string p = normalised(prediction);
  const bool said_stop = p == "stop";
  switch (answer.kind) {
    case QuestionKind::next_cell:
      if (said_stop)
        return "The walk stops in a cell only once a hit lies inside it (t of the hit <= the cell's exit t): "
               "traverse until tmin(next cell) > tmax(ray). Is there such a hit yet?";
      if (answer.stops)
        return "A hit found in this cell lies before the cell's exit, so no later cell can hold a nearer "
               "one: "
               "the walk stops here.";
      if (answer.walk == "octree")
        return "The next cell lies across the face the ray leaves through: the exit plane with the smallest "
               "t "
               "(t_exit per axis), not the nearest cell centre.";
      return "The 3D-DDA steps to the neighbour across the face the ray leaves through: the axis with the "
             "smallest tMax, which need not be the direction's largest component.";
    case QuestionKind::dda_axis:
      if (p == "none")
        return "The walk ends in this cell only with a hit before the cell's exit or when it leaves the "
               "grid.";
      return "Compare the three tMax values (the t where the ray reaches the next boundary on each axis): "
             "the "
             "smallest decides, not the largest direction component nor the nearest boundary in space.";
    case QuestionKind::first_child: {
      std::vector<std::string> parts = split_commas(p);
      const bool said_push = parts.size() == 2 && parts[1] == "push";
      const bool said_no_push = parts.size() == 2 && parts[1] == "nopush";
      if (answer.walk == "octree")
        return "Of the children the ray crosses, it enters first the one at its entry point: the entry plane "
               "is "
               "the one with the largest entry t; on each other axis it starts in the far half when it "
               "reaches "
               "that axis's centre plane before it enters the cell.";
      if (said_push && !answer.far_pushed)
        return "A far child is pushed only when the ray meets the plane inside the node: t* within "
               "[t_min, t_max]. Compare t* with the interval.";
      if (said_no_push && answer.far_pushed)
        return "t* lies within [t_min, t_max]: the ray crosses the plane inside the node, so the far child "
               "is needed later and waits on the stack.";
      return "The near child is the side of the plane the ray starts in; but compare t* with [t_min, t_max] "
             "first: when the ray crossed the plane before entering the node (0 <= t* < t_min) only the far "
             "child is visited.";
    }
    case QuestionKind::next_pop:
      if (said_stop)
        return "The walk stops only when the stack is empty or the top's t_min lies beyond the nearest hit: "
               "a "
               "node that starts before the hit may still hold a nearer one.";
      if (answer.stops)
        return "Every entry on the stack starts beyond the nearest hit (or none is left): nothing in them "
               "can "
               "be nearer, so the walk stops with the stack as it is.";
      return "The stack is last in, first out: the next node is the one pushed most recently (the top), the "
             "far child of the nearest split still open, not the first one pushed.";
    case QuestionKind::sah_plane:
      if (p == "leaf")
        return "A split pays when its cost C = t_t + p_a N_a t_i + p_b N_b t_i is below the leaf's N t_i: "
               "read the lowest point of the curves against the dashed line.";
      if (answer.axis < 0)
        return "Every candidate's cost lies above the leaf's N t_i (the dashed line): no split pays.";
      return "The SAH takes the lowest point of all three curves: not the longest axis, the middle of the "
             "node nor the median primitive. Read the minimum off the chart.";
    case QuestionKind::subdivide:
      if (answer.subdivided)
        return "The contrast (max - min) / (max + min) of the five first samples exceeds the threshold in "
               "some channel: the samples disagree, so the pixel is split.";
      return "The five first samples agree within the threshold: the contrast (max - min) / (max + min) "
             "stays below it, and the pixel keeps its 5 samples, even if a feature hides between them.";
    case QuestionKind::bvol_kind:
      if (p == "sphere" || p == "bvol-sphere")
        return "The smallest sphere around a flat or a long object is mostly empty: a ray that enters it "
               "usually passes beside the object. A sphere fits only round objects well.";
      return "Picture the empty space between each kind of volume and the object it encloses: the "
             "axis-aligned "
             "box fits walls in the axis planes exactly but not a turned or slanted object; more slabs (the "
             "14-DOP's diagonals) cut corners off; a box turned with the object (the oriented box) fits long "
             "slanted shapes.";
  }
  return "";
}

const char* question_kind_name(QuestionKind kind) {
  for (const KindInfo& k : kKinds)
    if (k.kind == kind) return k.name;
  return "?";
}

bool parse_question_kind(const std::string& name, QuestionKind* kind) {
  for (const KindInfo& k : kKinds)
    if (name == k.name) {
      *kind = k.kind;
      return true;
    }
  return false;
}

std::string question_walk(const QuestionContext& context) {
  return context.trace ? context.trace->structure.kind : std::string();
}

const char* question_prompt(QuestionKind kind, const std::string& walk) {
  if (walk == "octree" && kind == QuestionKind::first_child)
    return "Which child cell does the walk enter first (its octant, e.g. x+ y- z+, or its node id)?";
  if (walk == "octree" && kind == QuestionKind::next_cell)
    return "Which cell does the walk enter next (its octant or node id), or does it stop?";
  if (walk == "bsp" && kind == QuestionKind::first_child)
    return "Which child does the walk visit first (below or above the slanted plane), and is the far child "
           "pushed?";
  return question_prompt(kind);
}

const char* question_prompt(QuestionKind kind) {
  for (const KindInfo& k : kKinds)
    if (k.kind == kind) return k.prompt;
  return "";
}

}  // namespace raystep
