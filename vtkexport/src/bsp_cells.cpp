#include "bsp_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace raystep::vtk_export {

vtk_export::ConvexCell export_polytope(const raystep::ConvexCell& cell) {
  vtk_export::ConvexCell out;
  for (size_t f = 0; f < cell.face_count(); ++f) {
    std::vector<glm::vec3> face;
    const glm::dvec3* v = cell.face(f);
    for (size_t i = 0; i < cell.face_size(f); ++i) {
      const glm::vec3 p(v[i]);
      // Rounding to float may merge neighbouring vertices of a tiny face: keep each corner once.
      if (face.empty() || (p != face.back() && p != face.front())) face.push_back(p);
    }
    if (face.size() >= 3) out.faces.push_back(std::move(face));
  }
  return out;
}

std::vector<glm::vec3> plane_polygon(const raystep::ConvexCell& below, const glm::dvec3& n, double d) {
  // The cap is the face whose corners lie on the plane (cut points, up to rounding): the face with the
  // smallest largest distance, accepted if that distance is rounding-sized against the cell.
  double lo = 0.0, hi = 0.0;
  below.extent(n, &lo, &hi);
  const double scale = std::max({std::abs(lo), std::abs(hi), std::abs(d), hi - lo});
  size_t best = below.face_count();
  double best_dist = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < below.face_count(); ++f) {
    double dist = 0.0;
    for (size_t i = 0; i < below.face_size(f); ++i)
      dist = std::max(dist, std::abs(glm::dot(n, below.face(f)[i]) - d));
    if (dist < best_dist) best_dist = dist, best = f;
  }
  std::vector<glm::vec3> polygon;
  if (best == below.face_count() || !(best_dist <= 1e-9 * scale)) return polygon;
  for (size_t i = 0; i < below.face_size(best); ++i) polygon.emplace_back(below.face(best)[i]);
  return polygon;
}

std::unordered_map<int32_t, raystep::ConvexCell> bsp_trace_cells(const Trace& trace) {
  std::unordered_map<int32_t, const TraceNode*> by_id;
  for (const TraceNode& node : trace.nodes) by_id[node.id] = &node;
  // Parents first: a node is deeper than its parent.
  std::vector<const TraceNode*> order;
  for (const TraceNode& node : trace.nodes) order.push_back(&node);
  std::stable_sort(order.begin(), order.end(),
                   [](const TraceNode* a, const TraceNode* b) { return a->depth < b->depth; });
  std::unordered_map<int32_t, raystep::ConvexCell> cells;
  for (const TraceNode* node : order) {
    if (node->parent < 0) {
      cells[node->id] = raystep::ConvexCell::box(trace.structure.bounds);
      continue;
    }
    auto parent = by_id.find(node->parent);
    auto parent_cell = cells.find(node->parent);
    if (parent == by_id.end() || parent_cell == cells.end() || !parent->second->has_plane) {
      cells[node->id] = raystep::ConvexCell::box(node->box);
      continue;
    }
    const TraceNode& p = *parent->second;
    raystep::ConvexCell below, above;
    parent_cell->second.split(glm::dvec3(p.normal), double(p.offset), &below, &above);
    cells[node->id] = node->id == p.id + 1 ? std::move(below) : std::move(above);
  }
  return cells;
}

}  // namespace raystep::vtk_export
