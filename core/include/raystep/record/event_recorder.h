// The event recorder: the full log of one ray's traversal, for step-by-step replay and trace files.
// Pass it as the Recorder template parameter of a traversal kernel; call clear() between rays.
#pragma once

#include <vector>

#include "raystep/scene/geometry.h"
#include "raystep/record/events.h"

namespace raystep {

class EventRecorder {
 public:
  static constexpr bool enabled = true;

  void clear() {
    events_.clear();
    counters_ = {};
  }
  const std::vector<Event>& events() const { return events_; }
  const RayCounters& counters() const { return counters_; }

  void ray_begin(const Ray&) { add(EventType::ray_begin); }
  void cell(const GridCellStep& c) {
    Event& e = add(EventType::cell);
    e.cell[0] = c.i;
    e.cell[1] = c.j;
    e.cell[2] = c.k;
    e.t_enter = c.t_enter;
    e.t_exit = c.t_exit;
    e.t_max = c.t_max;
    e.t_delta = c.t_delta;
    e.next_axis = c.next_axis;
    ++counters_.cells;
  }
  void box_entered(uint32_t, float) {}
  void node(const TreeStep& s) {
    tree_event(EventType::node, s);
    ++counters_.nodes;
  }
  void push(const TreeStep& s) {
    tree_event(EventType::push, s);
    ++counters_.pushes;
  }
  void pop(const TreeStep& s) {
    tree_event(EventType::pop, s);
    ++counters_.pops;
  }
  void leaf(const TreeStep& s) { tree_event(EventType::leaf, s); }
  void box_test(const BoxTest& b) {
    Event& e = add(EventType::box_test);
    e.parent = b.parent;
    e.node = b.child;
    e.depth = b.depth;
    e.hit = b.hit;
    // A miss carries no interval: zeros, as the reader reads a box_test without t_near and t_far.
    e.t_min_node = b.hit ? b.t_near : 0.f;
    e.t_max_node = b.hit ? b.t_far : 0.f;
    ++counters_.box_tests;
  }
  void skip(const TreeStep& s) { tree_event(EventType::skip, s); }
  void prim_test(uint32_t prim, bool hit, float t) {
    Event& e = add(EventType::prim_test);
    e.prim = int32_t(prim);
    e.hit = hit;
    e.t = hit ? t : 0.f;
    ++counters_.prim_tests;
    counters_.prim_hits += hit;
  }
  void mailbox_hit(uint32_t prim) {
    add(EventType::mailbox_hit).prim = int32_t(prim);
    ++counters_.mailbox_hits;
  }
  void hit_deferred(uint32_t prim, float t, float t_cell_exit) {
    Event& e = add(EventType::hit_deferred);
    e.prim = int32_t(prim);
    e.t = t;
    e.t_exit = t_cell_exit;
  }
  void hit_accepted(uint32_t prim, float t, AcceptReason reason) {
    Event& e = add(EventType::hit_accepted);
    e.prim = int32_t(prim);
    e.t = t;
    e.reason = reason;
  }
  void ray_end(const Hit& hit) {
    Event& e = add(EventType::ray_end);
    e.prim = hit.prim;
    e.hit = hit.found();
    e.t = hit.found() ? hit.t : kInfinity;
  }

 private:
  void tree_event(EventType type, const TreeStep& s) {
    Event& e = add(type);
    e.node = s.node;
    e.depth = s.depth;
    e.t_min_node = s.t_min;
    e.t_max_node = s.t_max;
  }
  Event& add(EventType type) {
    Event e;
    e.seq = uint32_t(events_.size());
    e.type = type;
    events_.push_back(e);
    return events_.back();
  }
  std::vector<Event> events_;
  RayCounters counters_;
};

}  // namespace raystep
