#include "raystep/replay/replay_state.h"

#include <algorithm>
#include <limits>

#include "raystep/replay/replayer.h"

namespace raystep::replay {

const char* prim_state_name(PrimState s) {
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

const char* axis_name(int axis) {
  static const char* names[] = {"x", "y", "z"};
  return axis >= 0 && axis < 3 ? names[axis] : "none";
}

bool is_tree_event(EventType t) {
  return t == EventType::node || t == EventType::push || t == EventType::pop || t == EventType::leaf ||
         t == EventType::box_test || t == EventType::skip;
}

ReplayState replay_at(const TracedRay& ray, int step) {
  return Replayer(ray, std::numeric_limits<int>::max()).at(step);
}

int find_event(const TracedRay& ray, int from, EventType type, bool forward) {
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

int nth_event(const TracedRay& ray, EventType type, int k) {
  int seen = 0;
  for (size_t i = 0; i < ray.events.size(); ++i)
    if (ray.events[i].type == type && ++seen == k) return int(i);
  return -1;
}

bool is_tree_ray(const TracedRay& ray) {
  // The walk's first step tells (a grid's walk starts with a cell, a tree's with a node), so a long ray is not
  // read to its end.
  for (const Event& e : ray.events) {
    if (e.type == EventType::cell) return false;
    if (is_tree_event(e.type)) return true;
  }
  return false;
}

}  // namespace raystep::replay
