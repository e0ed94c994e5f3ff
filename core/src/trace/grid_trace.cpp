#include "raystep/trace/grid_trace.h"

#include <set>
#include <string>
#include <tuple>

#include "trace_recording.h"

namespace raystep {

Trace record_grid_trace(const Geometry& geometry, const UniformGrid& grid,
                        const std::vector<RayRequest>& rays, const std::string& scene_path,
                        const std::string& scene_hash) {
  Trace t = detail::begin_trace(geometry, "grid", scene_path, scene_hash);
  t.structure.bounds = grid.bounds();
  t.structure.resolution = grid.resolution();
  detail::add_param(&t.structure, "density", grid.options().density);
  detail::add_text_param(&t.structure, "resolution_from", grid.options().resolution ? "explicit" : "density");
  detail::add_text_param(&t.structure, "insert", grid.options().exact_insert ? "exact" : "bbox");
  detail::add_param(&t.structure, "references", double(grid.reference_count()));
  if (grid.coarsened()) {
    std::array<int, 3> r = grid.requested_resolution();
    std::string from = std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]);
    detail::add_text_param(&t.structure, "coarsened_from", from);
    detail::add_text_param(&t.structure, "coarsening", to_string(grid.coarsening()));
  }
  detail::sort_params(&t.structure);

  detail::record_traversals(geometry, rays, grid, &t);
  std::set<std::tuple<int, int, int>> cells;
  for (const TracedRay& tr : t.rays)
    for (const Event& e : tr.events)
      if (e.type == EventType::cell) cells.emplace(e.cell[0], e.cell[1], e.cell[2]);
  for (const auto& [i, j, k] : cells) t.cells.push_back(TraceCell{{i, j, k}, grid.cell_bounds(i, j, k)});
  return t;
}

}  // namespace raystep
