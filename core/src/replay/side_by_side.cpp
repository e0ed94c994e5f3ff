#include "raystep/replay/side_by_side.h"

#include <algorithm>
#include <cmath>

#include "raystep/geometry/numerics.h"
#include "raystep/trace/multi_trace.h"

namespace raystep::replay {

std::vector<std::string> parse_side_by_side_list(const std::string& list) {
  return parse_walk_list(list, "--compare '" + list + "'", kMinSideBySide, kMaxSideBySide);
}

namespace {

bool is_step(const Event& e) {
  return e.type == EventType::cell || e.type == EventType::node;
}
float entry_of(const Event& e) {
  return e.type == EventType::cell ? e.t_enter : e.t_min_node;
}

}  // namespace

WalkAtT walk_at_t(const TracedRay& ray, float t, const CostModel& model) {
  WalkAtT w;
  w.entered = -kInfinity;
  w.next = kInfinity;
  // walk_cost's position: a BVH enters boxes out of order, so the furthest entry so far.
  float position = -kInfinity;
  int last = int(ray.events.size()) - 1;
  for (size_t i = 0; i < ray.events.size(); ++i) {
    const Event& e = ray.events[i];
    if (is_step(e)) {
      const float p = std::max(position, entry_of(e));
      if (p > t) {  // the first step beyond t: the walk is shown just before it
        w.next = p;
        last = int(i) - 1;
        // ... and before the pops that lead there: a popped node (its t_min beyond t) is where the walk goes
        // next, not where it is (a pop costs nothing in the model).
        while (last > 0 && ray.events[size_t(last)].type == EventType::pop) --last;
        break;
      }
      position = p;
    }
  }
  w.step = std::max(last, 0);
  w.entered = position;
  for (int i = 0; i <= last; ++i) {
    const Event& e = ray.events[size_t(i)];
    if (is_step(e)) ++w.steps;
    if (e.type == EventType::prim_test) ++w.prim_tests;
    if (e.type == EventType::mailbox_hit) ++w.mailbox_hits;
    if (e.type == EventType::box_test) ++w.box_tests;
  }
  w.cost = model.t_t * w.steps + model.t_i * w.prim_tests;
  return w;
}

TimelineRange timeline_range(const std::vector<const TracedRay*>& rays) {
  float start = kInfinity, end = -kInfinity;
  for (const TracedRay* r : rays) {
    const WalkCost c = walk_cost(*r, CostModel{});
    for (const CostPoint& p : c.points)
      if (std::isfinite(p.t)) {
        start = std::min(start, p.t);
        end = std::max(end, p.t);
      }
  }
  if (!std::isfinite(start)) start = end = 0.f;
  if (!(end > start)) end = start + 1.f;  // one point: a timeline of some length, the walk done at its start
  return {start, end};
}

std::vector<std::pair<double, double>> cost_staircase(const WalkCost& cost, float start, float end) {
  std::vector<std::pair<double, double>> out;
  out.push_back({start, cost_at(cost, start)});
  for (const CostPoint& p : cost.points) {
    if (!(p.t > start) || !(p.t <= end)) continue;
    // Just before p.t the cost is cost_at of a t a hair below it; at p.t it steps up to cost_at(p.t).
    const double before = cost_at(cost, std::nextafter(p.t, -kInfinity));
    const double after = cost_at(cost, p.t);
    if (after == before) continue;
    out.push_back({p.t, before});
    out.push_back({p.t, after});
  }
  out.push_back({end, cost_at(cost, end)});
  return out;
}

}  // namespace raystep::replay
