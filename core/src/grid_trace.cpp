#include "raystep/trace/grid_trace.h"

#include <set>
#include <tuple>

#include "raystep/trace/event_recorder.h"

namespace raystep {

Trace record_grid_trace(const Geometry& geometry, const UniformGrid& grid, const std::vector<RayRequest>& rays,
                        const std::string& scene_path, const std::string& scene_hash) {
  Trace t;
  t.scene_path = scene_path;
  t.scene_hash = scene_hash;
  t.scene_primitives = geometry.size();
  t.structure.kind = "grid";
  t.structure.bounds = grid.bounds();
  t.structure.resolution = grid.resolution();
  auto param = [&](const char* key, double number) { t.structure.params.push_back({key, false, number, ""}); };
  param("density", grid.options().density);
  t.structure.params.push_back({"resolution_from", true, 0.0, grid.options().resolution ? "explicit" : "density"});
  t.structure.params.push_back({"insert", true, 0.0, grid.options().exact_insert ? "exact" : "bbox"});
  param("references", double(grid.reference_count()));
  std::sort(t.structure.params.begin(), t.structure.params.end(),
            [](const TraceParam& a, const TraceParam& b) { return a.key < b.key; });

  std::set<std::tuple<int, int, int>> cells;
  std::set<int32_t> prims;
  EventRecorder rec;
  for (const RayRequest& req : rays) {
    rec.clear();
    Hit hit;
    grid.traverse(req.ray, &hit, req.kind == RayKind::shadow, rec);
    TracedRay tr;
    tr.ray = req.ray;
    tr.kind = req.kind;
    tr.depth = req.depth;
    tr.has_pixel = req.has_pixel;
    tr.pixel[0] = req.pixel[0];
    tr.pixel[1] = req.pixel[1];
    tr.events = rec.events();
    for (const Event& e : tr.events) {
      if (e.type == EventType::cell) cells.emplace(e.cell[0], e.cell[1], e.cell[2]);
      if (e.prim >= 0) prims.insert(e.prim);
    }
    t.rays.push_back(std::move(tr));
  }
  for (const auto& [i, j, k] : cells) t.cells.push_back(TraceCell{{i, j, k}, grid.cell_bounds(i, j, k)});
  for (int32_t id : prims) {
    TracePrimitive p;
    p.id = id;
    p.type = geometry.type(uint32_t(id));
    if (p.type == PrimType::triangle) {
      for (int k = 0; k < 3; ++k) p.v[k] = geometry.vertex(uint32_t(id), k);
    } else {
      p.v[0] = geometry.sphere(uint32_t(id)).center;
      p.radius = geometry.sphere(uint32_t(id)).radius;
    }
    t.primitives.push_back(p);
  }
  return t;
}

}  // namespace raystep
