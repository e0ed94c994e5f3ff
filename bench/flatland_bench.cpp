// Dragging the ray in flatland: each move of the mouse re-traces the ray through the built structure of the
// 10,000-segment scene (scenes/flatland/dense_strokes.json), replays the walk to the step shown and makes the
// walk's layers of the figure over the still ones (core/figure/flat_figure.h: the cells or nodes of the walk,
// the ray, the caption), everything a 2D view does but painting. The aim is 16 ms a move (60 frames a
// second), for every structure. The structure's outline and the still layers (structure, names, shapes) are
// made once, when it is built, as a view keeps them.
//   raystep_bench_flatland [benchmark flags]
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "raystep/accel/plane_outline.h"
#include "raystep/accel/structure_options.h"
#include "raystep/figure/flat_figure.h"
#include "raystep/io/scene_loader.h"
#include "raystep/scene/flatland.h"
#include "raystep/trace/record_trace.h"

namespace raystep {
namespace {

void drag_the_ray(benchmark::State& state, const std::string& structure) {
  static const Scene scene =
      load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/flatland/dense_strokes.json");
  auto accel = make_accelerator(structure, StructureOptions{});
  accel->build(scene.geometry);
  const PlaneOutline outline = plane_outline(*accel);
  const Figure still = flat_figure_still(scene, &outline, nullptr);
  int move = 0;
  size_t events = 0, items = 0;
  for (auto _ : state) {
    // The direction turns a little with each move, as under a dragging hand.
    const float a = 0.55f + 0.002f * float(move++ % 200);
    const Ray ray = flat_ray(scene.flat->ray_origin, {std::cos(a), std::sin(a)});
    const Trace trace =
        record_trace(scene.geometry, *accel, {RayRequest{ray, RayKind::primary, 0, false, {0, 0}}},
                     "dense_strokes.json", "fnv1a64:0000000000000000");
    FlatFigureInput in;
    in.scene = &scene;
    in.outline = &outline;
    in.trace = &trace;
    in.step = int(trace.rays[0].events.size()) / 2;  // the step shown: kept where it still exists
    const FlatWalkLayers walk = flat_figure_walk(in, still);
    events += trace.rays[0].events.size();
    items += walk.walk.items.size() + walk.ray.items.size();
    benchmark::DoNotOptimize(walk);
  }
  state.counters["events"] = double(events) / double(state.iterations());
  state.counters["items"] = double(items) / double(state.iterations());
  state.counters["nodes"] = double(outline.total_nodes);
}

BENCHMARK_CAPTURE(drag_the_ray, grid, "grid")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, kd, "kd")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, kd_median, "kd-median")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, octree, "octree")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, bsp, "bsp")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, bvh, "bvh")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, bvh4, "bvh4")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(drag_the_ray, bvh8, "bvh8")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace raystep

BENCHMARK_MAIN();
