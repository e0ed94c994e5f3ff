// The side-by-side view's model (lecture: the variations of non-uniform subdivision, weighed on the same
// ray): the walks of one ray through several structures on ONE timeline over the ray's parameter t. At t each
// walk shows what it did before it entered its first cell or node beyond t (a step's entry t: the furthest
// cell t_enter or node t_min so far, as trace/walk_cost.h), so its counters and cost there are cost_at's.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "raystep/trace/trace_file.h"
#include "raystep/trace/walk_cost.h"

namespace raystep::replay {

constexpr int kMinSideBySide = 2;
constexpr int kMaxSideBySide = 4;  // four 3D views still leave each one readable on a 1280 x 800 screen

// "grid,kd,bvh": 2 to 4 structures that record events, each once, as `raystep trace --accel A,B,...` takes
// them. Throws InputError("", 0, "--compare 'grid,kd,grid': grid is listed twice") otherwise.
std::vector<std::string> parse_side_by_side_list(const std::string& list);

// What walk `ray` shows at t: the last event before its first cell or node entered beyond t and the pops that
// lead there (every event when no step is beyond t), and what it has counted up to and including that event.
struct WalkAtT {
  int step = 0;         // index of the event shown (replay_at's step)
  float entered = 0.f;  // the walk's position: the furthest entry t of its steps so far (-inf: none yet)
  float next = 0.f;     // the entry t of the step it makes next (+inf: none; always > t)
  uint32_t steps = 0, prim_tests = 0, mailbox_hits = 0, box_tests = 0;
  double cost = 0.0;  // t_t * steps + t_i * prim_tests: equal to cost_at(walk_cost(ray, model), t)
};
WalkAtT walk_at_t(const TracedRay& ray, float t, const CostModel& model);

// The timeline's range over the same ray of every walk: from the first entry (the smallest first step's entry
// t) to the furthest end (each walk's hit, or where it stopped); finite, start <= end.
struct TimelineRange {
  float start = 0.f, end = 1.f;
};
TimelineRange timeline_range(const std::vector<const TracedRay*>& rays);

// The walk's cumulative cost against t as a staircase to draw, from start to end: cost_at(cost, t) at every t
// of [start, end] (each riser drawn at the t where the cost steps up).
std::vector<std::pair<double, double>> cost_staircase(const WalkCost& cost, float start, float end);

}  // namespace raystep::replay
