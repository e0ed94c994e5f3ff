#include "raystep/replay/bvh_choice.h"

namespace raystep::replay {

bool is_bvh_kind(const std::string& kind) {
  return kind.rfind("bvh", 0) == 0;
}

bool is_bvh_ray(const Trace* trace, const TracedRay& ray) {
  if (trace) return is_bvh_kind(trace->structure.kind);
  // Without a trace, the walk's start tells: a BVH tests the children's boxes right after it enters a node.
  const std::vector<Event>& ev = ray.events;
  for (size_t i = 0; i < ev.size(); ++i) {
    if (ev[i].type == EventType::cell) return false;
    if (ev[i].type == EventType::box_test || ev[i].type == EventType::skip) return true;
    if (ev[i].type == EventType::node) return i + 1 < ev.size() && ev[i + 1].type == EventType::box_test;
  }
  return false;
}

BvhChoice bvh_choice(const TracedRay& ray, const ReplayState& s) {
  BvhChoice c;
  const std::vector<Event>& ev = ray.events;
  if (s.node_event < 0 || ev[size_t(s.node_event)].type != EventType::node) return c;
  c.node_event = s.node_event;
  c.node = ev[size_t(s.node_event)].node;
  // The node's box tests and pushes follow it; the next node event is the child entered first.
  size_t i = size_t(s.node_event) + 1;
  int last_test = -1;
  for (; i < ev.size(); ++i) {
    const Event& e = ev[i];
    if (e.type == EventType::box_test) {
      BoxTestMark m;
      m.child = e.node;
      m.hit = e.hit;
      m.t_near = e.t_min_node;
      m.t_far = e.t_max_node;
      m.event = int(i);
      m.done = int(i) <= s.step;
      c.tests.push_back(m);
      last_test = int(i);
    } else if (e.type == EventType::push) {
      c.pushed.push_back(e.node);
    } else {
      break;
    }
  }
  if (c.tests.empty()) return c;
  // (A wide BVH enters a leaf child with its leaf event: its leaves have no node event.)
  if (i < ev.size() && (ev[i].type == EventType::node || ev[i].type == EventType::leaf)) c.first = ev[i].node;
  c.decided = s.step >= last_test;
  c.valid = true;
  return c;
}

}  // namespace raystep::replay
