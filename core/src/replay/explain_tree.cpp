#include <algorithm>
#include <cmath>

#include "explain_parts.h"
#include "raystep/replay/explain.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/octree_choice.h"

namespace raystep::replay::detail {

namespace {

// A general BSP node's plane and decision, in the lecture's words: the same walk as the kd-tree's with
// t* = (d - n.o) / (n.dir) instead of (split - o.a) / d.a.
std::string explain_bsp_node(const Trace* trace, const NodeCrossing& c) {
  std::string head = "Inner " + node_name(trace, c.node) + ", plane n.p = d with n = " + vec(c.normal) +
                     ", d = " + num(c.offset) +
                     ".\nThe origin's signed distance n.o - d = " + num(float(c.origin_side)) + " (" +
                     (c.origin_side < 0 ? "below" : "above") +
                     " the plane); n.dir = " + num(float(c.n_dot_dir)) + ".\n";
  std::string near_name = node_name(trace, c.near_child) + " (" + side(c.near_is_below) + ")";
  std::string far_name = node_name(trace, c.far_child) + " (" + side(!c.near_is_below) + ")";
  if (c.crossing == Crossing::in_plane)
    return head +
           "n.dir is 0 within rounding and the ray lies on the plane, or too near it to tell: t* is "
           "undefined, "
           "the ray may touch both children over the whole interval.\nVisit the near child, " +
           near_name + "; push the far child, " + far_name + ", with all of [" + num(c.t_min) + ", " +
           num(c.t_max) + "].";
  if (!std::isfinite(c.t_star)) {
    std::string only = c.crossing == Crossing::near_only ? near_name : far_name;
    return head +
           "n.dir is 0 within rounding: the ray runs parallel to the plane and stays on its origin's "
           "side over [t_min, t_max].\nOnly " +
           only + " is visited: Intersect(" + (c.crossing == Crossing::near_only ? "near" : "far") +
           ", t_min, t_max).";
  }
  head += "t* = (d - n.o) / (n.dir) = " + num(c.t_star) +
          ". The near child is the side the ray starts in: " + side(c.near_is_below) +
          (c.n_dot_dir > 0 ? " (n.dir > 0: the ray moves up the normal)"
                           : " (n.dir < 0: the ray moves down the normal)") +
          ".\n";
  switch (c.crossing) {
    case Crossing::near_only:
      if (c.t_star < 0)
        return head + "t* = " + num(c.t_star) +
               " < 0: the plane lies behind the origin and the ray moves away from it, staying on its own "
               "side.\nOnly the near child, " +
               near_name + ", is visited: Intersect(near, t_min, t_max).";
      return head + "t* = " + num(c.t_star) + " > t_max = " + num(c.t_max) +
             ": the ray leaves the node's cell before it reaches the plane.\nOnly the near child, " +
             near_name + ", is visited: Intersect(near, t_min, t_max).";
    case Crossing::far_only:
      return head + "0 <= t* = " + num(c.t_star) + " < t_min = " + num(c.t_min) +
             ": the ray crossed the plane before it entered the node's cell.\nOnly the far child, " +
             far_name + ", is visited: Intersect(far, t_min, t_max).";
    case Crossing::both: {
      bool inside = c.t_star >= c.t_min && c.t_star <= c.t_max;
      return head +
             (inside ? "t_min = " + num(c.t_min) + " <= t* <= t_max = " + num(c.t_max)
                     : "t* is at the edge of [" + num(c.t_min) + ", " + num(c.t_max) +
                           "] (within the walk's rounding margin)") +
             ": the ray crosses both children.\nIntersect(near = " + near_name + ", t_min, t*) now; push " +
             "Intersect(far = " + far_name + ", t*, t_max) for later (t* widened to [" + num(c.t_lo) + ", " +
             num(c.t_hi) + "], its rounding bound, so no hit on the plane is lost).";
    }
    default:
      return head;
  }
}

// The octree's walk (Revelles et al.): the current inner cell's child order by its planes.
std::string octree_order_text(const OctreeChoice& c) {
  std::string t;
  if (c.entry_axis >= 0 && c.moving[c.entry_axis]) {
    t = "Entry plane: the ray enters the cell through its face normal to " +
        std::string(axis_name(c.entry_axis)) + " (t0." + axis_name(c.entry_axis) + " = " +
        num(c.t0[c.entry_axis]) + ", the largest entry t)";
  } else {
    t = "The ray starts inside the cell";
  }
  std::vector<std::string> crossed;
  for (int b = 0; b < c.axes; ++b)
    if (b != c.entry_axis && c.moving[b])
      crossed.push_back(
          std::string(axis_name(b)) + " centre plane at t = " + num(c.t_mid[b]) +
          (c.t_mid[b] < c.t0[c.entry_axis] ? " (before: the far half)" : " (after: the near half)"));
  if (!crossed.empty()) {
    t += "; ";
    for (size_t k = 0; k < crossed.size(); ++k) t += (k ? ", " : "") + crossed[k];
  }
  if (c.path.empty()) return t + ".";
  t += ".\nFirst child: " + std::to_string(c.path[0].node) + " [" + octant_name(c.path[0].octant, c.axes) + "].";
  t += " Next by the exit plane (the smallest exit t):";
  for (size_t k = 0; k < c.path.size(); ++k) {
    const OctreeChildStep& st = c.path[k];
    t += std::string(k ? ";" : "") + " " + std::to_string(st.node) + " leaves by " + axis_name(st.exit_axis) +
         (st.leaves_parent ? " (the cell's face) at t = " + num(st.t_exit) + ": done"
                           : " at t = " + num(st.t_exit) + " -> " + std::to_string(c.path[k + 1].node));
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
    if (c.visited[0] != planned[0] && c.path[0].t_exit < c.t_enter)
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

}  // namespace

std::string explain_octree_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const std::vector<Event>& ev = ray.events;
  size_t next = size_t(s.step) + 1;
  const Event* after = next < ev.size() ? &ev[next] : nullptr;
  std::string cell = "Cell " + std::to_string(e.node) + " (depth " + std::to_string(e.depth) +
                     ", [t_enter, t_exit] = [" + num(e.t_min_node) + ", " + num(e.t_max_node) + "])";
  switch (e.type) {
    case EventType::ray_begin: {
      int first = find_event(ray, 0, EventType::node, true);
      // A 2D scene's quadtree: its root is a square (a box of the walls' height over it).
      bool quad = false;
      if (trace)
        for (const TraceNode& n : trace->nodes) quad = quad || (!n.leaf && n.children.size() == 4);
      if (first < 0)
        return std::string("The ray misses the ") + (quad ? "quadtree's root square" : "octree's root cube") +
               " (slab test): no cell to visit.";
      const Event& root = ev[size_t(first)];
      return std::string("Slab test: the ray meets the root ") + (quad ? "square" : "cube") +
             " over [t_enter, t_exit] = [" + num(root.t_min_node) +
             ", " + num(root.t_max_node) +
             "]. The walk is parametric and top-down (Revelles et al.): from each cell to its children in "
             "the "
             "order the ray crosses them.";
    }
    case EventType::node: {
      if (after && after->type == EventType::leaf) return cell + " is a leaf.";
      const TraceNode* n = trace ? find_node(*trace, e.node) : nullptr;
      std::string text = cell + (n && n->children.size() == 4
                                     ? ": an inner cell, split at its centre into four quadrants (a quadtree: "
                                       "the plane's cells are cut on x and y only)."
                                     : ": an inner cell, split at its centre into eight octants.");
      if (OctreeChoice c = trace ? octree_choice(*trace, ray, s) : OctreeChoice{}; c.valid)
        text += "\n" + octree_order_text(c);
      return text;
    }
    case EventType::push: {
      std::string text =
          "Walk the children of cell " + std::to_string(e.node) +
          " in the order the ray crosses them (each child's [t_enter, t_exit] starts where the "
          "previous one's ends); its frame goes on the stack.";
      if (OctreeChoice c = trace ? octree_choice(*trace, ray, s) : OctreeChoice{}; c.valid && !c.path.empty())
        text +=
            " First child: " + std::to_string(c.path[0].node) + " [" + octant_name(c.path[0].octant, c.axes) + "].";
      return text;
    }
    case EventType::pop:
      return "Cell " + std::to_string(e.node) + "'s children are done" +
             (s.nearest_prim >= 0
                  ? " (or the next one starts beyond the nearest hit, t = " + num(s.nearest_t) + ")"
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
      std::string where =
          s.node_event >= 0 ? " in cell " + std::to_string(ev[size_t(s.node_event)].node) : "";
      return explain_prim_test(trace, ray, e, s, where);
    }
    case EventType::mailbox_hit:
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim && m.leaf >= 0)
          return "Mailbox hit: primitive " + std::to_string(e.prim) + " was already tested in cell " +
                 std::to_string(m.leaf) + " for this ray (it overlaps several cells): skip the test." +
                 mailbox_stamp(trace, ray, e.prim);
      return "Mailbox hit: primitive " + std::to_string(e.prim) +
             " was already tested for this ray: skipped." + mailbox_stamp(trace, ray, e.prim);
    case EventType::hit_deferred:
      return "The hit t = " + num(e.t) + " lies beyond this cell's exit, t_exit = " + num(e.t_exit) +
             ": a later cell may hold a nearer hit. Keep it and go on: traverse until tmin(cell) > "
             "tmax(ray).";
    case EventType::hit_accepted: {
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      if (e.reason == AcceptReason::inside_cell)
        return "Traverse until tmin(cell) > tmax(ray): the hit t = " + num(e.t) +
               " lies inside this cell (before its t_exit = " + num(s.t_max) +
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
std::string explain_tree_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const std::vector<Event>& ev = ray.events;
  size_t next = size_t(s.step) + 1;
  const Event* after = next < ev.size() ? &ev[next] : nullptr;
  switch (e.type) {
    case EventType::ray_begin: {
      int first = find_event(ray, 0, EventType::node, true);
      if (first < 0) return "The ray misses the tree's box (slab test): no node to visit.";
      const Event& root = ev[size_t(first)];
      return "Slab test: the ray meets the root's box over [t_min, t_max] = [" + num(root.t_min_node) + ", " +
             num(root.t_max_node) + "]; the walk starts at the root with that interval.";
    }
    case EventType::node: {
      if (after && after->type == EventType::leaf)
        return "Node " + std::to_string(e.node) + " (depth " + std::to_string(e.depth) + ") is a leaf.";
      NodeCrossing c = trace ? node_crossing(*trace, ray, s) : NodeCrossing{};
      if (!c.valid) return "Inner " + node_name(trace, e.node) + ": the walk goes on in its children.";
      std::string a = axis_name(c.axis);
      if (c.general) return explain_bsp_node(trace, c);
      // The near child: the side the ray starts in (the slides'); an origin on the plane, or on it within
      // rounding when both children are visited, starts in the side its direction points into.
      const float o = ray.ray.origin[c.axis], d = ray.ray.direction[c.axis];
      const bool starts_below = o < c.split;
      const std::string near_why =
          o != c.split && starts_below == c.near_is_below
              ? "The ray starts " + side(starts_below) + " (o." + a + " = " + num(o) +
                    "): that is the near side."
              : "The ray starts on the plane" + std::string(o == c.split ? "" : " within rounding") + " (o." +
                    a + " = " + num(o) + ") and moves " + (c.near_is_below ? "up" : "down") + " (d." + a +
                    " = " + num(d) + "): the near side is " + side(c.near_is_below) + ".";
      std::string head = "Inner " + node_name(trace, c.node) + " splits " + a + " at " + num(c.split) + ". " +
                         near_why + "\nt* = (split - o." + a + ") / d." + a + " = " + num(c.t_star) + ".\n";
      std::string near_name = node_name(trace, c.near_child) + " (" + side(c.near_is_below) + ")";
      std::string far_name = node_name(trace, c.far_child) + " (" + side(!c.near_is_below) + ")";
      switch (c.crossing) {
        case Crossing::near_only:
          if (std::isinf(c.t_star))
            return head + "The ray runs parallel to the plane (d." + a +
                   " = 0): it stays on one side.\nOnly " + near_name +
                   " is visited: Intersect(near, t_min, t_max).";
          if (c.t_star < 0)
            return head + "t* = " + num(c.t_star) +
                   " < 0: the plane lies behind the origin (near side: " + side(c.near_is_below) +
                   ", the side the ray starts in) and the ray moves away from it.\nOnly the near child, " +
                   near_name + ", is visited: Intersect(near, t_min, t_max).";
          return head + "t* = " + num(c.t_star) + " > t_max = " + num(c.t_max) +
                 ": the ray leaves the node before it reaches the plane.\nOnly the near child, " + near_name +
                 ", is visited: Intersect(near, t_min, t_max).";
        case Crossing::far_only:
          if (std::isinf(c.t_star))
            return head + "The ray runs parallel to the plane (d." + a +
                   " = 0): it stays on one side.\nOnly " + far_name +
                   " is visited: Intersect(far, t_min, t_max).";
          return head + "0 <= t* = " + num(c.t_star) + " < t_min = " + num(c.t_min) +
                 ": the ray crossed the plane before it entered the node.\nOnly the far child, " + far_name +
                 ", is visited: Intersect(far, t_min, t_max).";
        case Crossing::both: {
          bool inside = c.t_star >= c.t_min && c.t_star <= c.t_max;
          return head +
                 (inside ? "t_min = " + num(c.t_min) + " <= t* <= t_max = " + num(c.t_max)
                         : "t* is at the edge of [" + num(c.t_min) + ", " + num(c.t_max) +
                               "] (within the walk's rounding margin)") +
                 ": the ray crosses both children.\nIntersect(near = " + near_name +
                 ", t_min, t*) now; push (far = " + far_name + ", t*, t_max) for later.";
        }
        case Crossing::in_plane:
          return head +
                 "The ray lies in the split plane (t* = 0 * inf is undefined): it touches both children "
                 "over the whole interval.\nVisit the near child, " +
                 near_name + "; push the far child, " + far_name + ", with all of [" + num(c.t_min) + ", " +
                 num(c.t_max) + "].";
      }
      return head;
    }
    case EventType::push: {
      NodeCrossing c =
          trace ? node_crossing(*trace, ray, s) : NodeCrossing{};  // of the inner node being split
      bool in_plane = c.valid && c.crossing == Crossing::in_plane;
      return "Push the far child, " + node_name(trace, e.node) +
             (in_plane ? ", with the whole interval [t_min, t_max] = ["
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
      std::string head = "Pop " + node_name(trace, e.node) + " with [t_min, t_max] = [" + num(e.t_min_node) +
                         ", " + num(e.t_max_node) + "]. ";
      bool visited = after && after->type == EventType::node && after->node == e.node;
      if (visited) {
        if (s.nearest_prim < 0) return head + "No hit yet: visit it.";
        if (s.nearest_t < e.t_min_node)
          return head + "The nearest hit so far, t = " + num(s.nearest_t) +
                 ", lies before its t_min, but by less "
                 "than the walk's safety margin (2^-12 of the larger of |t_min| and |t_max| in the root): "
                 "visit it, "
                 "so that no hit is lost to rounding.";
        return head + "The nearest hit so far, t = " + num(s.nearest_t) +
               ", is not before its t_min: a nearer hit may "
               "lie in it, so visit it.";
      }
      const bool bsp = trace && trace->structure.kind == "bsp";
      if (bsp)  // t* is an interval there: the stack is not ordered by t_min
        return head + "The nearest hit t = " + num(s.nearest_t) + " < t_min = " + num(e.t_min_node) +
               ": the node starts beyond the hit, so none of its primitives can be nearer. Skip it. A BSP "
               "tree's stack is not ordered by t_min (t* is known within its rounding interval), so every "
               "entry left is popped and judged on its own.";
      return head + "The nearest hit t = " + num(s.nearest_t) + " < t_min = " + num(e.t_min_node) +
             ": the node starts beyond the hit, so none of its primitives can be nearer. Skip it." +
             (after && after->type == EventType::hit_accepted
                  ? " Every node under it on the stack starts later still."
                  : "");
    }
    case EventType::prim_test: {
      std::string where =
          s.node_event >= 0 ? " in leaf " + std::to_string(ev[size_t(s.node_event)].node) : "";
      return explain_prim_test(trace, ray, e, s, where);
    }
    case EventType::mailbox_hit:
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim && m.leaf >= 0)
          return "Primitive " + std::to_string(e.prim) + " was already tested in leaf " +
                 std::to_string(m.leaf) +
                 " for this ray (it lies in several leaves): the mailbox skips the test." +
                 mailbox_stamp(trace, ray, e.prim);
      return "Primitive " + std::to_string(e.prim) + " was already tested for this ray: skipped." +
             mailbox_stamp(trace, ray, e.prim);
    case EventType::hit_accepted: {
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      if (e.reason == AcceptReason::next_node_beyond) {
        int pop = find_event(ray, s.step, EventType::pop, false);
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

}  // namespace raystep::replay::detail
