#include "raystep/vtk_export/walk_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "bsp_cells.h"
#include "raystep/geometry/bounds.h"
#include "raystep/util/error.h"

namespace raystep::vtk_export {

namespace {

// Where the polyline ends for a ray without a hit: where it leaves the structure's box, or, for a ray that
// misses the box, as far along as the box reaches from the origin (the ray stays visible next to it).
float end_without_hit(const Ray& ray, const Bounds3& bounds, float t0) {
  float t_enter = 0.f, t_exit = 0.f;
  if (!bounds.empty() && intersect_slabs(bounds, ray, &t_enter, &t_exit) && std::isfinite(t_exit) &&
      t_exit > t0)
    return t_exit;
  const float speed = glm::length(ray.direction);
  float reach = 1.f;
  if (!bounds.empty() && speed > 0.f)
    reach = (glm::length(bounds.center() - ray.origin) + glm::length(bounds.extent())) / speed;
  if (!std::isfinite(reach) || reach <= 0.f) reach = 1.f;
  return std::min(t0 + reach, ray.tmax);
}

bool names_cell_or_node(EventType type) {
  switch (type) {
    case EventType::cell:
    case EventType::node:
    case EventType::push:
    case EventType::pop:
    case EventType::leaf:
    case EventType::box_test:
    case EventType::skip:
      return true;
    default:
      return false;
  }
}

}  // namespace

RayWalk ray_walk(const Trace& trace, size_t ray_index, const std::string& trace_name) {
  const TracedRay& tr = trace.rays.at(ray_index);
  RayWalk walk;

  // ---- the path ----
  RayPath& path = walk.path;
  const Ray& ray = tr.ray;
  const float t0 = std::max(ray.tmin, 0.f);
  float t_end = std::numeric_limits<float>::quiet_NaN();
  for (const Event& e : tr.events)
    if (e.type == EventType::ray_end && e.hit && std::isfinite(e.t)) {
      path.hit = true;
      path.prim = e.prim;
      t_end = e.t;
    }
  if (!path.hit) t_end = end_without_hit(ray, trace.structure.bounds, t0);
  path.points.push_back(ray.at(t0));
  path.t.push_back(t0);
  float t_in = 0.f, t_out = 0.f;
  if (!trace.structure.bounds.empty() && intersect_slabs(trace.structure.bounds, ray, &t_in, &t_out) &&
      t_in > t0 && t_in < t_end) {
    path.points.push_back(ray.at(t_in));
    path.t.push_back(t_in);
  }
  path.points.push_back(ray.at(t_end));
  path.t.push_back(t_end);

  // ---- the visited cells and nodes ----
  std::map<std::array<int, 3>, size_t> cell_of;
  for (size_t i = 0; i < trace.cells.size(); ++i)
    cell_of[{trace.cells[i].cell[0], trace.cells[i].cell[1], trace.cells[i].cell[2]}] = i;
  std::unordered_map<int32_t, size_t> node_of;
  for (size_t i = 0; i < trace.nodes.size(); ++i) node_of[trace.nodes[i].id] = i;

  std::unordered_map<int32_t, size_t> prim_of;
  for (size_t i = 0; i < trace.primitives.size(); ++i) prim_of[trace.primitives[i].id] = i;

  // A BSP tree's nodes are drawn as their convex cells (all of them: a CellSet is boxes or polytopes).
  const bool bsp = trace.structure.kind == "bsp";
  const std::unordered_map<int32_t, raystep::ConvexCell> bsp_cells =
      bsp ? bsp_trace_cells(trace) : std::unordered_map<int32_t, raystep::ConvexCell>{};

  CellSet& cs = walk.visited;
  int step = 0;
  for (const Event& e : tr.events) {
    if (e.type == EventType::prim_test || e.type == EventType::mailbox_hit) {
      auto it = prim_of.find(e.prim);
      if (it == prim_of.end())
        throw InputError(trace_name, 0,
                         "ray " + std::to_string(ray_index) + ", event " + std::to_string(e.seq) +
                             ": primitive " + std::to_string(e.prim) +
                             " is not among the trace's primitives");
      walk.tests.push_back(PrimitiveTest{trace.primitives[it->second], e.seq, e.type, e.hit, e.t});
      continue;
    }
    if (!names_cell_or_node(e.type)) continue;
    if (e.type == EventType::cell) {
      auto it = cell_of.find({e.cell[0], e.cell[1], e.cell[2]});
      if (it == cell_of.end())
        throw InputError(trace_name, 0,
                         "ray " + std::to_string(ray_index) + ", event " + std::to_string(e.seq) + ": cell " +
                             std::to_string(e.cell[0]) + "," + std::to_string(e.cell[1]) + "," +
                             std::to_string(e.cell[2]) + " is not among the trace's cells");
      cs.add_box(trace.cells[it->second].box);
      cs.set("i", e.cell[0], true);
      cs.set("j", e.cell[1], true);
      cs.set("k", e.cell[2], true);
      cs.set("t_enter", e.t_enter, false);
      cs.set("t_exit", e.t_exit, false);
    } else {
      auto it = node_of.find(e.node);
      if (it == node_of.end())
        throw InputError(trace_name, 0,
                         "ray " + std::to_string(ray_index) + ", event " + std::to_string(e.seq) + ": node " +
                             std::to_string(e.node) + " is not among the trace's nodes");
      const TraceNode& node = trace.nodes[it->second];
      if (bsp)
        cs.add_polytope(export_polytope(bsp_cells.at(node.id)));
      else
        cs.add_box(node.box);
      cs.set("node", e.node, true);
      cs.set("depth", e.depth, true);
      cs.set("leaf", node.leaf, true);
      // A missed box test has no interval.
      const bool interval = e.type != EventType::box_test || e.hit;
      cs.set("t_enter", interval ? double(e.t_min_node) : std::numeric_limits<double>::quiet_NaN(), false);
      cs.set("t_exit", interval ? double(e.t_max_node) : std::numeric_limits<double>::quiet_NaN(), false);
      if (e.type == EventType::box_test) cs.set("hit", e.hit, true);
    }
    cs.set("step", step++, true);
    cs.set("seq", e.seq, true);
    cs.set("event", int(e.type), true);
  }
  cs.finish();
  return walk;
}

}  // namespace raystep::vtk_export
