#include "raystep/trace/walk_cost.h"

#include <algorithm>
#include <cmath>

#include "trace_file_detail.h"

namespace raystep {

CostModel structure_cost_model(const TraceStructure& structure) {
  CostModel m;
  for (const TraceParam& p : structure.params) {
    if (p.is_text || !(p.number > 0.0) || !std::isfinite(p.number)) continue;
    if (p.key == "t_t")
      m.t_t = p.number;
    else if (p.key == "t_i")
      m.t_i = p.number;
  }
  return m;
}

WalkCost walk_cost(const TracedRay& ray, const CostModel& model) {
  WalkCost c;
  float position = -kInfinity;  // a BVH enters boxes out of order: the position is the furthest entry so far
  for (const Event& e : ray.events) {
    switch (e.type) {
      case EventType::cell:
      case EventType::node: {
        const float enter = e.type == EventType::cell ? e.t_enter : e.t_min_node;
        position = std::max(position, enter);
        c.points.push_back({position, c.total});
        c.total += model.t_t;
        break;
      }
      case EventType::prim_test:
        c.total += model.t_i;
        break;
      case EventType::ray_end:
        c.hit = e.prim >= 0;
        c.t_hit = e.t;
        break;
      default:
        break;
    }
  }
  c.points.push_back({std::max(position, c.t_hit), c.total});
  const RayCounters n = detail::count_events(ray.events);  // the counters every trace summary gives
  c.steps = n.cells + n.nodes;
  c.prim_tests = n.prim_tests;
  c.mailbox_hits = n.mailbox_hits;
  c.box_tests = n.box_tests;
  return c;
}

double cost_at(const WalkCost& cost, float t) {
  auto past = std::upper_bound(cost.points.begin(), cost.points.end(), t,
                               [](float value, const CostPoint& p) { return value < p.t; });
  return past == cost.points.end() ? cost.total : past->cost;
}

}  // namespace raystep
