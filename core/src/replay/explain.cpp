#include "raystep/replay/explain.h"

#include <algorithm>
#include <cstdio>

#include "explain_parts.h"
#include "raystep/geometry/exact.h"
#include "raystep/geometry/triangle.h"
#include "raystep/geometry/triangle_moller.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/trace/node_path.h"

namespace raystep::replay {

namespace detail {

std::string num(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", double(v));
  return buf;
}

}  // namespace detail

using namespace detail;

std::string describe_event(const Event& e) {
  std::string s = std::to_string(e.seq) + "  " + event_type_name(e.type);
  switch (e.type) {
    case EventType::cell:
      s += "  (" + std::to_string(e.cell[0]) + "," + std::to_string(e.cell[1]) + "," +
           std::to_string(e.cell[2]) + ")  t " + num(e.t_enter) + ".." + num(e.t_exit) + "  next " +
           axis_name(e.next_axis);
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
std::string mt_reason(const MollerTrumboreValues& m) {
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

std::string compare_triangle_tests(const TracedRay& ray, const TracePrimitive& p) {
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
         how + "); Möller–Trumbore " + (m.failed ? "miss (" + mt_reason(m) + ")" : std::string("hit")) + ".";
}

namespace detail {

namespace {

const TracePrimitive* find_primitive(const Trace* trace, int32_t id) {
  if (!trace) return nullptr;
  auto it = std::lower_bound(trace->primitives.begin(), trace->primitives.end(), id,
                             [](const TracePrimitive& p, int32_t v) { return p.id < v; });
  if (it != trace->primitives.end() && it->id == id) return &*it;
  for (const TracePrimitive& p : trace->primitives)
    if (p.id == id) return &p;
  return nullptr;
}

}  // namespace

// A primitive test in a cell or leaf (`where`): a nearer hit, a tie lost to a lower id, or no nearer hit; for
// a triangle, a second line with the watertight test and Möller–Trumbore on this very ray and triangle.
std::string explain_prim_test(const Trace* trace, const TracedRay& ray, const Event& e, const ReplayState& s,
                              const std::string& where) {
  std::string head = "Primitive " + std::to_string(e.prim) + where, text;
  if (e.hit && s.nearest_prim != e.prim)
    text = head + ": hit at t = " + num(e.t) + ", the same t as the nearest hit so far, primitive " +
           std::to_string(s.nearest_prim) + ": a tie goes to the lower id, which stays the nearest.";
  else if (e.hit && s.nearest_prim_before == e.prim)
    // Without mailboxes a primitive in several cells or leaves is tested again, and hits again at the same t.
    text = head + ": hit at t = " + num(e.t) +
           " again: it is already the nearest hit (tested before, in an "
           "earlier cell or leaf); the nearest hit stays.";
  else if (e.hit)
    text = head + ": hit at t = " + num(e.t) + ", nearer than any hit so far. It becomes the nearest hit.";
  else
    text = head + ": no hit nearer than the nearest so far.";
  if (const TracePrimitive* p = find_primitive(trace, e.prim)) {
    std::string line = compare_triangle_tests(ray, *p);
    if (!line.empty()) text += "\n" + line;
  }
  return text;
}

// The mailbox's mechanism (mailbox.h), for a skip: each ray takes the next number as it is cast, a test
// writes it into the primitive's mailbox, a mailbox that already holds the ray's own number means "tested":
// skip. Here the rays are numbered in the order the pixel cast them.
std::string mailbox_stamp(const Trace* trace, const TracedRay& ray, int32_t prim) {
  size_t number = 1;
  if (trace)
    for (size_t i = 0; i < trace->rays.size(); ++i)
      if (&trace->rays[i] == &ray) number = i + 1;
  return "\nPrimitive " + std::to_string(prim) + "'s mailbox holds ray number " + std::to_string(number) +
         ", this ray's own: each ray takes the next number as it is cast and writes it into the mailbox of "
         "every primitive it tests. The next ray's number matches no mailbox: nothing is cleared between "
         "rays.";
}

std::string cell_name(const int* c) {
  return "(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
}

// The 3D-DDA's step out of the cell of event `cell`: tMax, the smallest of it (the kernel's choice, ties to
// the lower axis), the next cell; or why the walk ends in this cell. The events after it are the truth.
std::string explain_dda_step(const TracedRay& ray, int cell) {
  const std::vector<Event>& ev = ray.events;
  const Event& e = ev[size_t(cell)];
  const std::string tmax = "tMax = " + vec(e.t_max);
  const int smallest = e.next_axis >= 0                                     ? e.next_axis
                       : (e.t_max.x <= e.t_max.y && e.t_max.x <= e.t_max.z) ? 0
                       : e.t_max.y <= e.t_max.z                             ? 1
                                                                            : 2;
  const std::string axis = axis_name(smallest);
  const std::string step = ray.ray.direction[smallest] > 0.f ? "+1" : "-1";
  const int next = find_event(ray, cell, EventType::cell, true);
  if (next >= 0)
    return tmax + ": the smallest is " + axis + ", so the 3D-DDA steps " + axis + " by " + step +
           " into cell " + cell_name(ev[size_t(next)].cell) + ".";
  // Why the walk ends here: a hit inside the cell, a shadow ray's first hit, or the grid's far side.
  const int accepted = find_event(ray, cell, EventType::hit_accepted, true);
  const Event* a = accepted >= 0 ? &ev[size_t(accepted)] : nullptr;
  const std::string would = tmax + ": the 3D-DDA would step " + axis + " by " + step + " next, but ";
  if (a && a->reason == AcceptReason::inside_cell)
    return would + "the hit at t = " + num(a->t) +
           " lies inside this cell: tmin(next cell) = t_exit = " + num(e.t_exit) +
           " > tmax(ray) = " + num(a->t) + ", so the walk ends in this cell.";
  if (a && a->reason == AcceptReason::any_hit)
    return would + "a shadow ray stops at its first hit, t = " + num(a->t) + ": the walk ends in this cell.";
  if (e.next_axis < 0)
    return tmax + ": the smallest, " + axis + " = " + num(e.t_max[smallest]) +
           ", lies beyond where the ray leaves the grid, t = " + num(e.t_exit) +
           ": the walk ends in this cell.";
  return tmax + ": the smallest is " + axis + ", but stepping " + axis + " by " + step +
         " leaves the grid: the walk ends in this cell.";
}

std::string explain_grid_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const Event* cell = s.cell_event >= 0 ? &ray.events[size_t(s.cell_event)] : nullptr;
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
      return explain_dda_step(ray, s.step);
    case EventType::ray_begin: {
      int first = find_event(ray, 0, EventType::cell, true);
      if (first < 0) return "Slab test: the ray misses the grid's box, so there is no cell to visit.";
      const Event& c = ray.events[size_t(first)];
      return "Slab test: the ray enters the grid's box at t = " + num(c.t_enter) +
             "; the walk starts in the cell that contains that point, " + cell_name(c.cell) + ".";
    }
    case EventType::prim_test: {
      std::string where = cell ? " in cell (" + std::to_string(cell->cell[0]) + "," +
                                     std::to_string(cell->cell[1]) + "," + std::to_string(cell->cell[2]) + ")"
                               : "";
      return explain_prim_test(trace, ray, e, s, where);
    }
    case EventType::mailbox_hit: {
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim)
          return "Primitive " + std::to_string(e.prim) + " was already tested in cell (" +
                 std::to_string(m.cell[0]) + "," + std::to_string(m.cell[1]) + "," +
                 std::to_string(m.cell[2]) +
                 ") for this ray (it spans several cells): the mailbox skips the test." +
                 mailbox_stamp(trace, ray, e.prim);
      return "Primitive " + std::to_string(e.prim) + " was already tested for this ray: skipped." +
             mailbox_stamp(trace, ray, e.prim);
    }
    default:
      return "";
  }
}

std::string side(bool below) {
  return below ? "below the plane" : "above the plane";
}

// "node 2 (LL)": the id the trace uses and the path in the slides' notation (none for a wide BVH's node).
std::string node_name(const Trace* trace, int32_t id) {
  if (id < 0) return "the child";
  const std::string path = trace ? trace_node_path_text(*trace, id) : "";
  return "node " + std::to_string(id) + (path.empty() ? "" : " (" + path + ")");
}

std::string vec(const glm::vec3& v) {
  return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")";
}
}  // namespace detail

std::string explain_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  if (!s.event) return "";
  if (is_bvh_ray(trace, ray)) return explain_bvh_rule(trace, ray, s);
  if (is_octree_ray(trace, ray)) return explain_octree_rule(trace, ray, s);
  return is_tree_ray(ray) ? explain_tree_rule(trace, ray, s) : explain_grid_rule(trace, ray, s);
}

}  // namespace raystep::replay
