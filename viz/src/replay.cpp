#include "replay.h"

#include <algorithm>
#include <cstdio>
#include <unordered_map>

namespace raystep::viz {

const char* primStateName(PrimState s) {
  switch (s) {
    case PrimState::pending: return "pending";
    case PrimState::testing: return "testing";
    case PrimState::hit: return "hit";
    case PrimState::missed: return "missed";
    case PrimState::skipped: return "skipped (mailbox)";
  }
  return "";
}

const char* axisName(int axis) {
  static const char* names[] = {"x", "y", "z"};
  return axis >= 0 && axis < 3 ? names[axis] : "none";
}

namespace {

bool isTreeEvent(EventType t) {
  return t == EventType::node || t == EventType::push || t == EventType::pop || t == EventType::leaf;
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
      case EventType::push:
      case EventType::pop:
      case EventType::leaf:
        s.nodeEvent = i;
        s.hasInterval = true;
        s.tMin = e.t_min_node;
        s.tMax = e.t_max_node;
        if (e.type == EventType::node) ++s.counters.nodes;
        if (e.type == EventType::push) {
          ++s.counters.pushes;
          s.stack.push_back(StackEntry{e.node, e.depth, e.t_min_node, e.t_max_node});
        }
        if (e.type == EventType::pop) {
          ++s.counters.pops;
          if (!s.stack.empty()) s.stack.pop_back();
        }
        break;
      case EventType::prim_test: {
        ++s.counters.prim_tests;
        MailboxEntry m;
        m.prim = e.prim;
        m.testedInCellEvent = s.cellEvent;
        if (s.cellEvent >= 0) std::copy(ev[size_t(s.cellEvent)].cell, ev[size_t(s.cellEvent)].cell + 3, m.cell);
        m.hit = e.hit;
        m.t = e.t;
        tested.emplace(e.prim, s.mailbox.size());
        s.mailbox.push_back(m);
        if (e.hit) {
          ++s.counters.prim_hits;
          s.nearestPrim = e.prim;
          s.nearestT = e.t;
          s.deferred = false;
        }
        break;
      }
      case EventType::mailbox_hit:
        ++s.counters.mailbox_hits;
        if (auto it = tested.find(e.prim); it != tested.end()) ++s.mailbox[it->second].skips;
        break;
      case EventType::hit_deferred: s.deferred = true; break;
      case EventType::hit_accepted:
        s.accepted = true;
        s.deferred = false;
        s.reason = e.reason;
        s.nearestPrim = e.prim;
        s.nearestT = e.t;
        break;
      case EventType::ray_end: s.ended = true; break;
      default: break;
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
      if (int(i) > step) p.state = PrimState::pending;
      else if (e.type == EventType::mailbox_hit) p.state = PrimState::skipped;
      else if (int(i) == step) p.state = PrimState::testing;
      else p.state = e.hit ? PrimState::hit : PrimState::missed;
      p.t = e.t;
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

std::string describeEvent(const Event& e) {
  std::string s = std::to_string(e.seq) + "  " + event_type_name(e.type);
  switch (e.type) {
    case EventType::cell:
      s += "  (" + std::to_string(e.cell[0]) + "," + std::to_string(e.cell[1]) + "," + std::to_string(e.cell[2]) +
           ")  t " + num(e.t_enter) + ".." + num(e.t_exit) + "  next " + axisName(e.next_axis);
      break;
    case EventType::node:
    case EventType::push:
    case EventType::pop:
    case EventType::leaf:
      s += "  node " + std::to_string(e.node) + " depth " + std::to_string(e.depth) + "  t " + num(e.t_min_node) +
           ".." + num(e.t_max_node);
      break;
    case EventType::prim_test:
      s += "  prim " + std::to_string(e.prim) + (e.hit ? ": hit at t " + num(e.t) : ": miss");
      break;
    case EventType::mailbox_hit: s += "  prim " + std::to_string(e.prim) + " skipped (tested before)"; break;
    case EventType::hit_deferred:
      s += "  prim " + std::to_string(e.prim) + " t " + num(e.t) + " > cell exit " + num(e.t_exit);
      break;
    case EventType::hit_accepted:
      s += "  prim " + std::to_string(e.prim) + " t " + num(e.t) + " (" + accept_reason_name(e.reason) + ")";
      break;
    case EventType::ray_end:
      s += e.prim >= 0 ? "  hit prim " + std::to_string(e.prim) + " at t " + num(e.t) : "  miss";
      break;
    default: break;
  }
  return s;
}

std::string explainRule(const TracedRay& ray, const ReplayState& s) {
  if (!s.event) return "";
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
      if (e.reason == AcceptReason::any_hit) return "Shadow ray: any hit will do  =>  stop at t = " + num(e.t) + ".";
      return "The walk left the grid; the nearest hit t = " + num(e.t) + " is final.";
    case EventType::ray_end:
      if (e.prim < 0) return "Miss: the walk left the grid without a hit.";
      return "Result: primitive " + std::to_string(e.prim) + " at t = " + num(e.t) + ".";
    case EventType::cell:
      if (e.next_axis < 0)
        return "min t_max = " + num(std::min({e.t_max.x, e.t_max.y, e.t_max.z})) + " > t_exit(grid) = " + num(e.t_exit) +
               ": the walk ends in this cell.";
      return "Step along " + std::string(axisName(e.next_axis)) + ": t_max." + axisName(e.next_axis) + " = " +
             num(e.t_max[e.next_axis]) + " is the smallest t_max.";
    case EventType::ray_begin: {
      int first = findEvent(ray, 0, EventType::cell, true);
      if (first < 0) return "The ray misses the grid's box (slab test): no cell to visit.";
      return "Slab test: the ray enters the grid's box at t = " + num(ray.events[size_t(first)].t_enter) +
             "; the walk starts in the cell that contains that point.";
    }
    case EventType::prim_test: {
      std::string where = cell ? " in cell (" + std::to_string(cell->cell[0]) + "," + std::to_string(cell->cell[1]) +
                                     "," + std::to_string(cell->cell[2]) + ")"
                               : "";
      if (e.hit)
        return "Primitive " + std::to_string(e.prim) + where + ": hit at t = " + num(e.t) +
               ", nearer than any hit so far. It becomes the nearest hit.";
      return "Primitive " + std::to_string(e.prim) + where + ": no hit nearer than the nearest so far.";
    }
    case EventType::mailbox_hit: {
      for (const MailboxEntry& m : s.mailbox)
        if (m.prim == e.prim)
          return "Primitive " + std::to_string(e.prim) + " was already tested in cell (" + std::to_string(m.cell[0]) +
                 "," + std::to_string(m.cell[1]) + "," + std::to_string(m.cell[2]) +
                 ") for this ray (it spans several cells): the mailbox skips the test.";
      return "Primitive " + std::to_string(e.prim) + " was already tested for this ray: skipped.";
    }
    default: return "";
  }
}

}  // namespace raystep::viz
