#include <algorithm>

#include "explain_parts.h"
#include "raystep/accel/bvh_names.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/explain.h"

namespace raystep::replay::detail {

namespace {

// The decision at an inner BVH node once its children's boxes are tested: enter the nearer box hit, push the
// others, or (none hit) go on with the stack.
std::string bvh_decision(const BvhChoice& c) {
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
           num(hits[0]->t_near) + ", " + num(hits[0]->t_far) + "].";
  std::string text = std::to_string(hits.size()) + " children's boxes are hit";
  // Overlapping intervals: the boxes overlap along the ray (bounding volumes can overlap).
  bool overlap = false;
  for (size_t a = 0; a < hits.size(); ++a)
    for (size_t b = a + 1; b < hits.size(); ++b)
      overlap |= hits[a]->t_near <= hits[b]->t_far && hits[b]->t_near <= hits[a]->t_far;
  if (overlap)
    text += ", and their intervals overlap: the boxes overlap along the ray (bounding volumes can overlap)";
  if (!first) return text + ".";
  bool by_distance = true;
  for (const BoxTestMark* m : hits) by_distance &= first->t_near <= m->t_near;
  text += ".\nNearer first: enter child " + std::to_string(first->child) +
          " (t_near = " + num(first->t_near) + ")";
  bool tie = false;
  for (const BoxTestMark* m : hits) tie |= m != first && m->t_near == first->t_near;
  text += !by_distance ? " (chosen by the ray's direction on the split axis, not by t_near)"
          : tie        ? " (a tie: the same t_near, so the child tested first goes first)"
                       : "";
  if (!c.pushed.empty()) {
    text += "; push ";
    for (size_t k = 0; k < c.pushed.size(); ++k) {
      if (k) text += ", ";
      text += "child " + std::to_string(c.pushed[k]);
      for (const BoxTestMark* m : hits)
        if (m->child == c.pushed[k]) text += " (t_near = " + num(m->t_near) + ")";
    }
    text += " for later.";
  } else {
    text += ".";
  }
  return text;
}

}  // namespace

// The BVH's stack walk in the lecture's words: tight boxes, possibly overlapping, tested child by child.
std::string explain_bvh_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s) {
  const Event& e = *s.event;
  const std::vector<Event>& ev = ray.events;
  size_t next = size_t(s.step) + 1;
  const Event* after = next < ev.size() ? &ev[next] : nullptr;
  switch (e.type) {
    case EventType::ray_begin: {
      int first = find_event(ray, 0, EventType::node, true);
      if (first < 0) return "The ray misses the root's box (slab test): no node to visit.";
      const Event& root = ev[size_t(first)];
      return "Slab test: the ray meets the root's box over [t_near, t_far] = [" + num(root.t_min_node) +
             ", " + num(root.t_max_node) + "]; the walk starts at the root.";
    }
    case EventType::node: {
      if (after && after->type == EventType::leaf)
        return "Node " + std::to_string(e.node) + " (depth " + std::to_string(e.depth) + ") is a leaf.";
      BvhChoice c = bvh_choice(ray, s);
      return "Inner " + node_name(trace, e.node) + " (depth " + std::to_string(e.depth) +
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
        text += s.nearest_prim >= 0
                    ? "its box is missed: the ray does not enter it before the nearest hit so far, t = " +
                          num(s.nearest_t) + ", so nothing under it can give a nearer hit."
                    : std::string(
                          "its box is missed (the slab intervals do not overlap): nothing under it can "
                          "be hit.");
      BvhChoice c = bvh_choice(ray, s);
      if (c.valid && c.decided) text += "\n" + bvh_decision(c);
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
      const std::optional<BvhName> name = trace ? parse_bvh_name(trace->structure.kind) : std::nullopt;
      if (name && name->builder == BvhBuilder::sbvh)
        return head + ": test its " + std::to_string(k) + (k == 1 ? " primitive" : " primitives") +
               ". No mailbox: spatial splits cut some primitives in two, so such a primitive sits in several "
               "leaves (once in each) and a ray that reaches two of them tests it twice (the structure line "
               "gives the references per primitive).";
      return head + ": test its " + std::to_string(k) + (k == 1 ? " primitive" : " primitives") +
             ". No mailbox: in a BVH each primitive is in exactly one leaf, so no primitive is tested twice "
             "for a ray (the kd-tree needs mailboxes because it copies a primitive into every cell it "
             "overlaps).";
    }
    case EventType::pop: {
      std::string head = "Pop " + node_name(trace, e.node) + " with t_near = " + num(e.t_min_node) + ". ";
      if (after && after->type == EventType::skip) return head + "Is its box beyond the nearest hit?";
      if (s.nearest_prim < 0) return head + "No hit yet: visit it.";
      return head + "The nearest hit so far, t = " + num(s.nearest_t) +
             ", is not before its t_near: a nearer hit may lie in its box (the boxes overlap, or the hit "
             "lies "
             "beyond it), so visit it.";
    }
    case EventType::skip:
      return "skip: t_near = " + num(e.t_min_node) + " > t of the nearest hit = " + num(s.nearest_t) +
             ": the box starts beyond the hit, so nothing in it can be nearer. Skip node " +
             std::to_string(e.node) + " without testing its children.";
    case EventType::prim_test: {
      std::string where =
          s.node_event >= 0 ? " in leaf " + std::to_string(ev[size_t(s.node_event)].node) : "";
      return explain_prim_test(trace, ray, e, s, where);
    }
    case EventType::hit_accepted: {
      if (e.reason == AcceptReason::any_hit)
        return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      if (e.reason == AcceptReason::next_node_beyond) {
        int pop = find_event(ray, s.step, EventType::pop, false);
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

}  // namespace raystep::replay::detail
