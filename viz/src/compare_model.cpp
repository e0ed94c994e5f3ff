#include "compare_model.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/geometry/numerics.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"

namespace raystep::viz {

std::vector<std::string> parseCompareList(const std::string& list) {
  const std::string option = "--compare '" + list + "'";
  std::vector<std::string> names;
  size_t start = 0;
  while (true) {
    const size_t comma = list.find(',', start);
    names.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (names.size() > size_t(kMaxCompareViews))
    throw InputError("", 0,
                     option + ": " + std::to_string(names.size()) + " structures, at most " +
                         std::to_string(kMaxCompareViews) + " side by side");
  const std::vector<std::string> known = accelerator_names();
  std::set<std::string> seen;
  for (const std::string& n : names) {
    if (n.empty()) throw InputError("", 0, option + ": an empty name (names are separated by single commas)");
    if (std::find(known.begin(), known.end(), n) == known.end() && !parse_bvol_kind(n)) {
      std::string all;
      for (const std::string& k : known) all += (all.empty() ? "" : ", ") + k;
      throw InputError("", 0, option + ": unknown structure '" + n + "' (one of " + all + ")");
    }
    if (!seen.insert(n).second) throw InputError("", 0, option + ": " + n + " is listed twice");
    if (!records_events(*make_accelerator(n)))
      throw InputError(
          "", 0,
          option + ": " + n +
              " records no events (use grid, kd, kd-median, bvh, bvh-sweep, bvh-median, bvh4, bvh8, "
              "octree or bsp)");
  }
  if (names.size() < size_t(kMinCompareViews))
    throw InputError("", 0,
                     option + ": give " + std::to_string(kMinCompareViews) + " to " +
                         std::to_string(kMaxCompareViews) + " structures, separated by commas");
  return names;
}

namespace {

bool isStep(const Event& e) {
  return e.type == EventType::cell || e.type == EventType::node;
}
float entryOf(const Event& e) {
  return e.type == EventType::cell ? e.t_enter : e.t_min_node;
}

}  // namespace

WalkAtT walkAtT(const TracedRay& ray, float t, const CostModel& model) {
  WalkAtT w;
  w.entered = -kInfinity;
  w.next = kInfinity;
  // walk_cost's position: a BVH enters boxes out of order, so the furthest entry so far.
  float position = -kInfinity;
  int last = int(ray.events.size()) - 1;
  for (size_t i = 0; i < ray.events.size(); ++i) {
    const Event& e = ray.events[i];
    if (isStep(e)) {
      const float p = std::max(position, entryOf(e));
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
    if (isStep(e)) ++w.steps;
    if (e.type == EventType::prim_test) ++w.primTests;
    if (e.type == EventType::mailbox_hit) ++w.mailboxHits;
    if (e.type == EventType::box_test) ++w.boxTests;
  }
  w.cost = model.t_t * w.steps + model.t_i * w.primTests;
  return w;
}

TimelineRange timelineRange(const std::vector<const TracedRay*>& rays) {
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

std::vector<std::pair<double, double>> costStaircase(const WalkCost& cost, float start, float end) {
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

}  // namespace raystep::viz
