// A recorded walk's cost along the ray, by the lecture's cost model: t_t per traversal step (a grid cell or a
// tree node visited) and t_i per primitive test (a mailbox hit costs nothing: that is its point). The cost
// against the ray's parameter t says where each structure is when the ray reaches t, and where one pulls
// ahead.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/trace/trace_file.h"

namespace raystep {

struct CostModel {
  double t_t = 1.0;   // per traversal step
  double t_i = 80.0;  // per primitive test
};

// The structure's own constants where its trace records them (params "t_t", "t_i": kd, bsp, bvh), else the
// lecture's t_t = 1, t_i = 80.
CostModel structure_cost_model(const TraceStructure& structure);

struct CostPoint {
  float t = 0.f;      // the walk's position along the ray: the furthest entry t reached so far
  double cost = 0.0;  // the cost spent before the walk entered there
};

struct WalkCost {
  uint32_t steps = 0;  // cells + nodes visited
  uint32_t prim_tests = 0, mailbox_hits = 0, box_tests = 0;
  double total = 0.0;  // t_t * steps + t_i * prim_tests
  bool hit = false;
  float t_hit = 0.f;  // the nearest hit's t (a miss: the ray_end's t)
  // One point per step whose entry t is known (a cell's t_enter, a node's t_min), in event order, then the
  // end (t_hit or the furthest position, total). Both t and cost never decrease; the last cost is total.
  std::vector<CostPoint> points;
};

WalkCost walk_cost(const TracedRay& ray, const CostModel& model);

// The cost the walk spent before it moved beyond t (the cost of the first point past t; total if none).
double cost_at(const WalkCost& cost, float t);

}  // namespace raystep
